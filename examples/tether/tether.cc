#include "tether.h"

#include "core/input_error.h"

namespace tether {

std::string BuildTether(ipstep::TermBuilder& builder, const nlohmann::json& parameters) {
  const std::string& file = builder.scene().source;
  const int dimension = builder.scene().dimension;
  if (!parameters.is_object()) {
    throw ipstep::InputError(file, "tether", "must be an object {\"stiffness\": k, \"point\": p}");
  }
  for (const auto& item : parameters.items()) {
    if (item.key() != "stiffness" && item.key() != "point") {
      throw ipstep::InputError(file, "tether." + item.key(), "unknown key (stiffness, point)");
    }
  }
  const nlohmann::json k =
      parameters.contains("stiffness") ? parameters.at("stiffness") : nlohmann::json();
  if (!k.is_number() || !(k.get<double>() > 0.0) || !(k.get<double>() <= 1e12)) {
    throw ipstep::InputError(file, "tether.stiffness", "must be a number in (0, 1e12] N/m");
  }
  std::array<double, 3> point = {0.0, 0.0, 0.0};
  if (parameters.contains("point")) {
    const nlohmann::json& p = parameters.at("point");
    if (!p.is_array() || static_cast<int>(p.size()) != dimension) {
      throw ipstep::InputError(file, "tether.point",
                               "must be an array of " + std::to_string(dimension) + " numbers");
    }
    for (int c = 0; c < dimension; ++c) {
      if (!p[c].is_number() || !(std::abs(p[c].get<double>()) <= 1e6)) {
        throw ipstep::InputError(file, "tether.point[" + std::to_string(c) + "]",
                                 "must be a number in [-1e6, 1e6] m");
      }
      point[c] = p[c].get<double>();
    }
  }
  int count = 0;
  for (int i = 0; i < builder.state().num_nodes(); ++i) {
    if (!builder.state().is_free(i)) continue;
    builder.AddAutoDiff<Tether, ipstep::kOneResidualPerCoordinate, 1>(ipstep::TermKind::kPotential,
                                                                      {i}, k.get<double>(), point);
    ++count;
  }
  return "tether: " + std::to_string(count) + " terms";
}

void RegisterTether(ipstep::EffectRegistry& registry) {
  registry.Register("tether", "pull every free node towards a point", BuildTether);
}

}  // namespace tether
