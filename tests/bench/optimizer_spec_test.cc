// ipstep_bench's optimiser specs (bench/optimizer_spec.h): each key sets the
// OptimizerOptions field of its option row, takes that row's type and range,
// and applies to the optimisers the row says, as the ipstep flag of the same
// option does.
#include "bench/optimizer_spec.h"

#include <string>

#include <gtest/gtest.h>

#include "core/input_error.h"

namespace ipstep {
namespace bench {
namespace {

// The error's text for `spec`, or "" when it parses.
std::string ErrorOf(const std::string& spec) {
  try {
    ParseOptimizerSpec(spec, 1e-6);
  } catch (const InputError& error) {
    return error.what();
  }
  return "";
}

TEST(OptimizerSpec, KeysSetTheirRowsFields) {
  const OptimizerSpec newton = ParseOptimizerSpec(
      "newton+sparse=EIGEN_SPARSE+radius=1e8+backtrack=false+threads=2+"
      "max_iterations=7+ordering=AMD+projection=abs",
      1e-6);
  EXPECT_EQ(newton.options.optimizer, Optimizer::kNewton);
  EXPECT_EQ(newton.options.tolerance, 1e-6);
  EXPECT_EQ(newton.options.sparse_library, "EIGEN_SPARSE");
  EXPECT_EQ(newton.options.initial_trust_region_radius, 1e8);
  EXPECT_FALSE(newton.options.backtrack_rejected_steps);
  EXPECT_EQ(newton.options.num_threads, 2);
  EXPECT_EQ(newton.options.max_iterations, 7);
  EXPECT_EQ(newton.options.linear_solver_ordering, "AMD");
  EXPECT_EQ(newton.options.hessian_projection, HessianProjection::kAbsolute);
  const OptimizerSpec ncg = ParseOptimizerSpec("ncg+type=POLAK_RIBIERE+line_search=WOLFE", 1e-6);
  EXPECT_EQ(ncg.options.nonlinear_cg, "POLAK_RIBIERE");
  EXPECT_EQ(ncg.options.line_search, "WOLFE");
  EXPECT_EQ(ParseOptimizerSpec("lbfgs+rank=5", 1e-6).options.lbfgs_rank, 5);
  EXPECT_TRUE(ParseOptimizerSpec("none", 1e-6).none);
  // projected_newton takes the sparse Cholesky's options, as --sparse_library does.
  EXPECT_EQ(ParseOptimizerSpec("projected_newton+sparse=EIGEN_SPARSE", 1e-6).options.sparse_library,
            "EIGEN_SPARSE");
}

TEST(OptimizerSpec, ValuesAreCheckedByTheirRows) {
  EXPECT_EQ(ErrorOf("newton+radius=0"),
            "optimizer spec: newton+radius=0: radius: must be in [1e-12, 1e20] (omit it for newton "
            "and gauss_newton 1e16, dogleg 1e4), got 0");
  EXPECT_EQ(ErrorOf("lbfgs+rank=0").find("optimizer spec: lbfgs+rank=0: rank: must be in [1, "),
            0u);
  EXPECT_EQ(ErrorOf("lbfgs+rank=2.5"),
            "optimizer spec: lbfgs+rank=2.5: rank: must be an integer, got '2.5'");
  EXPECT_EQ(ErrorOf("newton+threads=1e300"),
            "optimizer spec: newton+threads=1e300: threads: must be an integer, got '1e300'");
  EXPECT_EQ(ErrorOf("newton+radius=inf"),
            "optimizer spec: newton+radius=inf: radius: not a finite number, got 'inf'");
  EXPECT_EQ(ErrorOf("newton+backtrack=1"),
            "optimizer spec: newton+backtrack=1: backtrack: must be true or false, got '1'");
  EXPECT_NE(ErrorOf("newton+sparse=MKL").find("unknown sparse library 'MKL'"), std::string::npos);
}

TEST(OptimizerSpec, KeysApplyWhereTheirRowsSay) {
  EXPECT_EQ(ErrorOf("newton+rank=5"),
            "optimizer spec: newton+rank=5: rank applies to lbfgs, bfgs, ncg and "
            "gradient_descent, not to optimizer=newton");
  EXPECT_EQ(ErrorOf("lbfgs+backtrack=true"),
            "optimizer spec: lbfgs+backtrack=true: backtrack applies to newton, dogleg and "
            "gauss_newton, not to optimizer=lbfgs");
  EXPECT_EQ(ErrorOf("none+rank=3"),
            "optimizer spec: none+rank=3: 'none' (no optimiser) takes no keys");
  EXPECT_EQ(ErrorOf("newton+foo=1").find("optimizer spec: newton+foo=1: unknown key 'foo' ("), 0u);
  EXPECT_EQ(ErrorOf("newton+radius"), "optimizer spec: newton+radius: 'radius' is not key=value");
  EXPECT_EQ(ErrorOf(""), "optimizer spec: : empty");
}

}  // namespace
}  // namespace bench
}  // namespace ipstep
