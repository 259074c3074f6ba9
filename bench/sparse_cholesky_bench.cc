// The floor of a Newton iteration's linear algebra: one scene's projected
// Newton matrix (projected_newton's, assembled after one step so that the
// step weights and the state are a real step's) factorised by each sparse
// Cholesky of solver/sparse_cholesky.h, timed alone (docs/benchmarks.md,
// "Sparse Cholesky"):
//   sparse_cholesky_bench SCENE [integrator=quasi_static] [repeats=3] [grid_size]
// Prints the matrix (unknowns, nonzeros of its lower triangle), the time of
// one assembly of the matrix (every term's model, projected, summed), and per
// library and ordering: nonzeros of the factor, the symbolic analysis, the
// numeric factorisation (the fastest of `repeats`) and one solve.
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>
#include <vector>

#include "core/input_error.h"
#include "core/scoped_timer.h"
#include "problems/scene_loader.h"
#include "sim/default_effects.h"
#include "sim/run_trajectory.h"
#include "sim/simulation.h"
#include "solver/node_ordering.h"
#include "solver/projected_newton_solver.h"
#include "solver/sparse_cholesky.h"

namespace {

struct Case {
  const char* name;
  ipstep::SparseLibrary library;
  ipstep::FillOrdering ordering;
  bool node_order;  // the nodes' nested dissection, given to CHOLMOD
};

}  // namespace

int main(int argc, char** argv) {
  using namespace ipstep;
  if (argc < 2) {
    std::fprintf(stderr, "usage: sparse_cholesky_bench SCENE [integrator] [repeats] [grid_size]\n");
    return 2;
  }
  const std::string integrator = argc > 2 ? argv[2] : "quasi_static";
  const int repeats = argc > 3 ? std::max(1, std::atoi(argv[3])) : 3;
  try {
    SceneLoadOptions load;
    load.extra_effects = DefaultEffects().UserNames();
    if (argc > 4) load.grid_size = std::atoi(argv[4]);
    const Scene scene = LoadScene(argv[1], load);
    SimulationOptions options;
    options.integrator.name = integrator;
    options.optimizer.optimizer = Optimizer::kProjectedNewton;
    options.optimizer.hessian_projection = HessianProjection::kWhenIndefinite;
    options.steps = 1;
    Simulation sim(scene, options);
    ProjectedNewtonSolver* solver = nullptr;
    IncrementalPotential* potential = nullptr;
    sim.ReplaceStepSolver([&](IncrementalPotential* p, const State* s) {
      auto made = std::make_unique<ProjectedNewtonSolver>(p, s, options.optimizer);
      solver = made.get();
      potential = p;
      return made;
    });
    StepReport report;
    RunOptions run;
    run.after_step = [&report](const StepReport& r) { report = r; };
    const double step_seconds = RunTrajectory(sim, run).wall_seconds;
    auto start = WallClock::now();
    if (!solver->AssembleHessian(sim.state().x)) {
      std::fprintf(stderr, "the Hessian cannot be evaluated at the step's result\n");
      return 1;
    }
    const double assemble = SecondsSince(start);
    const Eigen::SparseMatrix<double> matrix = solver->hessian();
    std::printf("scene %s, %s: one step %s in %d iterations, %.3f s\n", scene.name.c_str(),
                integrator.c_str(), report.status.c_str(), report.iterations, step_seconds);
    std::printf("matrix: %ld unknowns, %ld nonzeros (lower triangle); assembly %.1f ms\n",
                static_cast<long>(matrix.rows()), static_cast<long>(matrix.nonZeros()),
                1e3 * assemble);
    // The nodes' nested dissection expanded to the free unknowns.
    start = WallClock::now();
    const std::vector<int> nodes = NestedDissectionNodeOrder(*potential, sim.state());
    std::vector<int> permutation;
    const int dim = sim.state().dimension;
    for (int node : nodes) {
      for (int k = 0; k < dim; ++k) {
        const int free = solver->free_index()[dim * node + k];
        if (free >= 0) permutation.push_back(free);
      }
    }
    const double node_ordering = SecondsSince(start);
    const Eigen::VectorXd rhs = Eigen::VectorXd::Ones(matrix.rows());
    Eigen::VectorXd solution;
    const Case cases[] = {
        {"CHOLMOD supernodal, AMD", SparseLibrary::kSuiteSparse, FillOrdering::kAmd, false},
        {"CHOLMOD supernodal, METIS of the unknowns", SparseLibrary::kSuiteSparse,
         FillOrdering::kNestedDissection, false},
        {"CHOLMOD supernodal, METIS of the nodes", SparseLibrary::kSuiteSparse,
         FillOrdering::kNestedDissection, true},
        {"Eigen SimplicialLDLT, AMD", SparseLibrary::kEigen, FillOrdering::kAmd, false},
    };
    std::printf("%-44s %12s %12s %14s %10s\n", "factorisation", "nnz(L)", "analyse ms",
                "factorise ms", "solve ms");
    for (const Case& c : cases) {
      if (c.node_order && static_cast<int>(permutation.size()) != matrix.rows()) continue;
      auto cholesky = SparseCholesky::Create(c.library, c.ordering);
      start = WallClock::now();
      if (!cholesky->Analyze(matrix, c.node_order ? &permutation : nullptr)) {
        std::printf("%-44s analysis failed\n", c.name);
        continue;
      }
      double analyse = SecondsSince(start);
      if (c.node_order) analyse += node_ordering;
      double factorise = 1e300;
      SparseCholesky::Result result = SparseCholesky::Result::kFailure;
      for (int r = 0; r < repeats; ++r) {
        start = WallClock::now();
        result = cholesky->Factorize(matrix);
        factorise = std::min(factorise, SecondsSince(start));
      }
      start = WallClock::now();
      const bool solved =
          result == SparseCholesky::Result::kSuccess && cholesky->Solve(rhs, &solution);
      const double solve = SecondsSince(start);
      std::printf("%-44s %12.4g %12.1f %14.1f %10.1f%s\n", c.name, cholesky->FactorNonZeros(),
                  1e3 * analyse, 1e3 * factorise, 1e3 * solve,
                  solved ? "" : "  (not positive definite)");
    }
  } catch (const InputError& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 2;
  }
  return 0;
}
