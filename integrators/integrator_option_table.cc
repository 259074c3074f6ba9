#include "integrators/integrator_option_table.h"

namespace ipstep {
namespace {

OptionTable<IntegratorOptions> Build() {
  OptionTable<IntegratorOptions> t;
  OptionRow<IntegratorOptions> name = MakeOptionRow<IntegratorOptions>(
      "integrator", "IntegratorOptions.name", "integrator", OptionType::kString,
      std::string("backward_euler"), "backward_euler | newmark | quasi_static | symplectic_euler");
  BindField(&IntegratorOptions::name, &name);
  t.push_back(name);
  const auto newmark_only = [](const IntegratorOptions& o, const std::string& prefix) {
    return o.name == "newmark" ? std::string() : "applies to " + prefix + "integrator=newmark only";
  };
  OptionRow<IntegratorOptions> beta =
      WithRange(MakeOptionRow<IntegratorOptions>("newmark_beta", "IntegratorOptions.newmark_beta",
                                                 "newmark_beta", OptionType::kDouble, 0.25,
                                                 "Newmark beta (integrators/newmark.h)"),
                1e-3, 1.0, "");
  BindField(&IntegratorOptions::newmark_beta, &beta);
  beta.applies = newmark_only;
  t.push_back(beta);
  OptionRow<IntegratorOptions> gamma =
      WithRange(MakeOptionRow<IntegratorOptions>("newmark_gamma", "IntegratorOptions.newmark_gamma",
                                                 "newmark_gamma", OptionType::kDouble, 0.5,
                                                 "Newmark gamma (integrators/newmark.h)"),
                0.5, 1.0, "");
  BindField(&IntegratorOptions::newmark_gamma, &gamma);
  gamma.applies = newmark_only;
  t.push_back(gamma);
  return t;
}

}  // namespace

const OptionTable<IntegratorOptions>& IntegratorOptionTable() {
  static const OptionTable<IntegratorOptions> table = Build();
  return table;
}

}  // namespace ipstep
