#include "tether.h"

#include <algorithm>
#include <vector>

#include "core/json_node.h"

namespace tether {

std::string BuildTether(ipstep::TermBuilder& builder, const nlohmann::json& parameters) {
  // Each check throws one ipstep::InputError naming the file and the key:
  // "tethered_square.json: tether.stiffness: must be in (0, 1e12] N/m, got -1".
  const ipstep::JsonNode tether(parameters, "tether", builder.scene().source);
  tether.ExpectObject({"stiffness", "point"});
  const double k = tether.Get("stiffness").InRange(0.0, 1e12, "N/m", /*min_open=*/true);
  std::array<double, 3> point = {0.0, 0.0, 0.0};
  if (const auto p = tether.Find("point")) {
    const std::vector<double> given = p->Position(builder.scene().dimension);  // |p_i| <= 1e6 m
    std::copy(given.begin(), given.end(), point.begin());
  }
  int count = 0;
  for (int i = 0; i < builder.state().num_nodes(); ++i) {
    if (!builder.state().is_free(i)) continue;
    builder.AddAutoDiff<Tether, ipstep::kOneResidualPerCoordinate, 1>(ipstep::TermKind::kPotential,
                                                                      {i}, k, point);
    ++count;
  }
  return "tether: " + std::to_string(count) + " terms";
}

void RegisterTether(ipstep::EffectRegistry& registry) {
  registry.Register("tether", "pull every free node towards a point", BuildTether);
}

}  // namespace tether
