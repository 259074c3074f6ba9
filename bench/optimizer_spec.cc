#include "bench/optimizer_spec.h"

#include <cmath>
#include <map>
#include <sstream>
#include <vector>

#include "core/input_error.h"
#include "core/option_table.h"
#include "core/parse_number.h"
#include "solver/optimizer_option_table.h"

namespace ipstep {
namespace bench {
namespace {

// The spec's keys and the option rows they stand for (optimizer_spec.h).
const std::map<std::string, std::string>& SpecKeys() {
  static const std::map<std::string, std::string> keys = {{"sparse", "sparse_library"},
                                                          {"radius", "initial_trust_region_radius"},
                                                          {"backtrack", "backtrack_rejected_steps"},
                                                          {"linear_solver", "linear_solver"},
                                                          {"ordering", "linear_solver_ordering"},
                                                          {"threads", "num_threads"},
                                                          {"max_iterations", "max_iterations"},
                                                          {"line_search", "line_search"},
                                                          {"rank", "lbfgs_rank"},
                                                          {"type", "nonlinear_cg"},
                                                          {"projection", "hessian_projection"}};
  return keys;
}

std::string KeyList() {
  std::string list;
  for (const auto& [key, row] : SpecKeys()) list += (list.empty() ? "" : ", ") + key;
  return list;
}

// `value` as the row's type; throws InputError naming the spec and key.
OptionValue ValueOf(const OptionRow<OptimizerOptions>& row, const std::string& spec,
                    const std::string& key, const std::string& value) {
  const auto fail = [&](const std::string& what) {
    throw InputError("optimizer spec", spec,
                     key + ": " + what + ", got '" + ClipInput(value) + "'");
  };
  switch (row.type) {
    case OptionType::kString:
      return value;
    case OptionType::kBool:
      if (value != "true" && value != "false") fail("must be true or false");
      return value == "true";
    case OptionType::kInt:
    case OptionType::kDouble:
      break;
  }
  double number = 0.0;
  if (!ParseFiniteNumber(value, &number)) fail("not a finite number");
  if (row.type == OptionType::kDouble) return number;
  if (number != std::floor(number) || std::fabs(number) > 1e15) fail("must be an integer");
  return static_cast<long long>(number);
}

}  // namespace

OptimizerSpec ParseOptimizerSpec(const std::string& text, double tolerance) {
  OptimizerSpec spec;
  spec.text = text;
  std::vector<std::string> parts;
  std::stringstream stream(text);
  for (std::string part; std::getline(stream, part, '+');) parts.push_back(part);
  if (parts.empty() || parts[0].empty()) throw InputError("optimizer spec", text, "empty");
  const std::string& name = parts[0];
  spec.none = name == "none";
  spec.options.tolerance = tolerance;
  if (!spec.none) spec.options.optimizer = ParseOptimizer(name);
  for (size_t p = 1; p < parts.size(); ++p) {
    const size_t eq = parts[p].find('=');
    if (eq == std::string::npos) {
      throw InputError("optimizer spec", text, "'" + ClipInput(parts[p]) + "' is not key=value");
    }
    const std::string key = parts[p].substr(0, eq), value = parts[p].substr(eq + 1);
    if (spec.none) {
      throw InputError("optimizer spec", text, "'none' (no optimiser) takes no keys");
    }
    const auto found = SpecKeys().find(key);
    if (found == SpecKeys().end()) {
      throw InputError("optimizer spec", text,
                       "unknown key '" + ClipInput(key) + "' (" + KeyList() + ")");
    }
    const OptionRow<OptimizerOptions>& row = *FindOption(OptimizerOptionTable(), found->second);
    if (row.applies) {
      const std::string why = row.applies(spec.options, "");
      if (!why.empty()) throw InputError("optimizer spec", text, key + " " + why);
    }
    try {
      SetOption(row, ValueOf(row, text, key, value), &spec.options);
    } catch (const InputError& error) {
      // "options: <field>: <why>" (core/option_table.h), told by the spec's key.
      const std::string what = error.what(), prefix = "options: " + row.field + ": ";
      if (what.rfind(prefix, 0) != 0) throw;
      throw InputError("optimizer spec", text, key + ": " + what.substr(prefix.size()));
    }
  }
  // Validates the options now (a bad spec is an input error, not a run failure).
  switch (spec.none ? OptimizerFamily::kEigenNewton : FamilyOf(spec.options.optimizer)) {
    case OptimizerFamily::kTrustRegion:
      MakeTrustRegionOptions(spec.options);
      break;
    case OptimizerFamily::kLineSearch:
      MakeLineSearchOptions(spec.options);
      break;
    case OptimizerFamily::kEigenNewton:
      ValidateOptimizerOptions(spec.options);
      break;
  }
  return spec;
}

}  // namespace bench
}  // namespace ipstep
