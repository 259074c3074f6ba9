#include "core/json_node.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>

#include "core/input_error.h"
#include "core/input_limits.h"

namespace ipstep {

using nlohmann::json;

std::string FormatNumber(double value) {
  if (std::isnan(value)) return "nan";
  if (std::isinf(value)) return value > 0 ? "inf" : "-inf";
  char buffer[32];
  for (int precision = 1; precision <= 17; ++precision) {
    std::snprintf(buffer, sizeof(buffer), "%.*g", precision, value);
    if (std::strtod(buffer, nullptr) == value) break;
  }
  return buffer;
}

std::string Quoted(const std::string& text) { return "\"" + ClipInput(text) + "\""; }

std::string Describe(const json& value) {
  switch (value.type()) {
    case json::value_t::object:
      return "an object";
    case json::value_t::array:
      return "an array of " + std::to_string(value.size()) + " elements";
    case json::value_t::string: {
      std::string text = value.get_ref<const std::string&>();
      if (text.size() > 40) text = text.substr(0, 37) + "...";
      return "the string " + json(text).dump(-1, ' ', false, json::error_handler_t::replace);
    }
    case json::value_t::number_integer:
    case json::value_t::number_unsigned:
      return value.dump();
    case json::value_t::number_float:
      return FormatNumber(value.get<double>());
    case json::value_t::boolean:
      return value.get<bool>() ? "true" : "false";
    case json::value_t::null:
      return "null";
    default:
      return value.type_name();
  }
}

void JsonNode::FailAt(const std::string& path, const std::string& what) const {
  throw InputError(*source_, path.empty() ? "(top level)" : path, what);
}

void JsonNode::ExpectObject(const std::vector<std::string>& allowed) const {
  if (!value_->is_object()) Fail("must be an object, got " + Describe(*value_));
  for (const auto& item : value_->items()) {
    bool known = false;
    for (const std::string& key : allowed) known |= key == item.key();
    if (!known) {
      std::string list;
      for (const std::string& key : allowed) list += (list.empty() ? "" : ", ") + key;
      FailAt(ChildPath(item.key()), "unknown key (allowed keys: " + list + ")");
    }
  }
}

std::optional<JsonNode> JsonNode::Find(const std::string& key) const {
  if (!Has(key)) return std::nullopt;
  return JsonNode((*value_)[key], ChildPath(key), *source_);
}

JsonNode JsonNode::Get(const std::string& key) const {
  if (!Has(key)) FailAt(ChildPath(key), "required key is missing");
  return JsonNode((*value_)[key], ChildPath(key), *source_);
}

std::vector<JsonNode> JsonNode::Elements() const {
  if (!value_->is_array()) Fail("must be an array, got " + Describe(*value_));
  std::vector<JsonNode> elements;
  elements.reserve(value_->size());
  for (size_t i = 0; i < value_->size(); ++i) {
    elements.emplace_back((*value_)[i], path_ + "[" + std::to_string(i) + "]", *source_);
  }
  return elements;
}

double JsonNode::Number() const {
  if (!value_->is_number()) Fail("must be a number, got " + Describe(*value_));
  const double number = value_->get<double>();
  if (!std::isfinite(number)) Fail("must be finite, got " + FormatNumber(number));
  return number;
}

double JsonNode::InRange(double min, double max, const std::string& unit, bool min_open,
                         const std::string& note) const {
  const double number = Number();
  if (!(min_open ? number > min : number >= min) || !(number <= max)) {
    Fail("must be in " + limits::RangeText(min, max, unit, min_open) + note + ", got " +
         FormatNumber(number));
  }
  return number;
}

double JsonNode::Positive() const {
  const double number = Number();
  if (!(number > 0)) Fail("must be > 0, got " + FormatNumber(number));
  return number;
}

int64_t JsonNode::Integer() const {
  if (value_->is_number_unsigned()) {
    const uint64_t number = value_->get<uint64_t>();
    if (number > static_cast<uint64_t>(std::numeric_limits<int64_t>::max())) {
      Fail("is out of range, got " + Describe(*value_));
    }
    return static_cast<int64_t>(number);
  }
  if (!value_->is_number_integer()) Fail("must be an integer, got " + Describe(*value_));
  return value_->get<int64_t>();
}

int JsonNode::IntegerInRange(int64_t min, int64_t max) const {
  const int64_t number = Integer();
  if (number < min || number > max) {
    Fail("must be an integer in [" + std::to_string(min) + ", " + std::to_string(max) + "], got " +
         std::to_string(number));
  }
  return static_cast<int>(number);
}

bool JsonNode::Bool() const {
  if (!value_->is_boolean()) Fail("must be true or false, got " + Describe(*value_));
  return value_->get<bool>();
}

std::string JsonNode::String() const {
  if (!value_->is_string()) Fail("must be a string, got " + Describe(*value_));
  return value_->get<std::string>();
}

std::vector<double> JsonNode::Vector(int size, double bound, const std::string& unit) const {
  if (!value_->is_array() || static_cast<int>(value_->size()) != size) {
    Fail("must be an array of " + std::to_string(size) + " numbers (the scene's dimension), got " +
         Describe(*value_));
  }
  std::vector<double> vector;
  for (const JsonNode& element : Elements()) {
    const double number = element.Number();
    if (!(std::abs(number) <= bound)) {
      element.Fail("must be in " + limits::RangeText(-bound, bound, unit) + ", got " +
                   FormatNumber(number));
    }
    vector.push_back(number);
  }
  return vector;
}

std::vector<double> JsonNode::Position(int size) const {
  return Vector(size, limits::kMaxCoordinate, "m");
}

std::vector<double> JsonNode::Velocity(int size) const {
  return Vector(size, limits::kMaxSpeed, "m/s");
}

Eigen::Vector3d JsonNode::Vector3(int size, double bound, const std::string& unit) const {
  const std::vector<double> v = Vector(size, bound, unit);
  Eigen::Vector3d out = Eigen::Vector3d::Zero();
  for (int k = 0; k < size && k < 3; ++k) out[k] = v[k];
  return out;
}

}  // namespace ipstep
