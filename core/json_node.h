// Reading JSON input with strict validation: a JSON value together with its
// key path ("springs[3].stiffness") and its source (a file name), so that
// every check reports where it failed as one InputError "source: path: what".
// The scene loader (problems/scene_loader.h, its solid: problems/solid_loader.h)
// and every effect's parameters (built-in or user-written,
// energies/effect_registry.h) are read with it; examples/tether/tether.cc:
//
//   const JsonNode tether(parameters, "tether", builder.scene().source);
//   tether.ExpectObject({"stiffness", "point"});
//   const double k = tether.Get("stiffness").InRange(0.0, 1e12, "N/m", /*min_open=*/true);
//   if (const auto p = tether.Find("point")) ... p->Position(builder.scene().dimension) ...
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <nlohmann/json.hpp>

namespace ipstep {

// Shortest decimal form that reads back as the same double ("nan", "inf").
std::string FormatNumber(double value);
// A name from the input, quoted and cut for a message.
std::string Quoted(const std::string& text);
// A short description of a JSON value for "got ..." in messages (containers
// are only named).
std::string Describe(const nlohmann::json& value);

class JsonNode {
 public:
  // `value` and `source` must outlive the node and the nodes made from it.
  JsonNode(const nlohmann::json& value, std::string path, const std::string& source)
      : value_(&value), path_(std::move(path)), source_(&source) {}

  const nlohmann::json& value() const { return *value_; }
  const std::string& path() const { return path_; }
  const std::string& source() const { return *source_; }

  // Throw InputError(source, path, what).
  [[noreturn]] void Fail(const std::string& what) const { FailAt(path_, what); }
  [[noreturn]] void FailAt(const std::string& path, const std::string& what) const;
  std::string ChildPath(const std::string& key) const {
    return path_.empty() ? key : path_ + "." + key;
  }

  // Requires an object whose keys all appear in `allowed`.
  void ExpectObject(const std::vector<std::string>& allowed) const;
  bool Has(const std::string& key) const { return value_->is_object() && value_->contains(key); }
  std::optional<JsonNode> Find(const std::string& key) const;
  // Fails with "required key is missing" when absent.
  JsonNode Get(const std::string& key) const;
  // Requires an array.
  std::vector<JsonNode> Elements() const;

  // A finite number.
  double Number() const;
  // A number in [min, max] (or (min, max] with `min_open`); `unit` and `note`
  // for the message.
  double InRange(double min, double max, const std::string& unit = "", bool min_open = false,
                 const std::string& note = "") const;
  double Positive() const;
  int64_t Integer() const;
  int IntegerInRange(int64_t min, int64_t max) const;
  bool Bool() const;
  std::string String() const;
  // An array of `size` numbers, each in [-bound, bound].
  std::vector<double> Vector(int size, double bound, const std::string& unit) const;
  std::vector<double> Position(int size) const;  // bounded by limits::kMaxCoordinate [m]
  std::vector<double> Velocity(int size) const;  // bounded by limits::kMaxSpeed [m/s]
  // The same as a 3-vector (components beyond `size` zero).
  Eigen::Vector3d Vector3(int size, double bound, const std::string& unit) const;

 private:
  const nlohmann::json* value_;
  std::string path_;
  const std::string* source_;
};

}  // namespace ipstep
