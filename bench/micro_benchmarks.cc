// Google Benchmark micro-benchmarks of the hot paths (docs/benchmarks.md):
//   BM_Term/<element>            residual + Jacobian of one autodiff term
//   BM_EnergyGradient/<n>        E and grad E of a whole cloth step (n x n nodes)
//   BM_TermModel/<spring>/<how>  projected Newton model of one spring
//                                (core/term_hessian.h): analytic over d, central
//                                differences over d, central differences over
//                                all parameters (no pair reduction)
//   BM_ReferenceHessian/<n>      projected per-term Hessians + sparse assembly
//   BM_NewtonIteration/<n>       one Newton iteration from the start of a cloth
//                                step: Ceres newton (LM, CX_SPARSE) and the Eigen
//                                reference projected Newton
//   BM_FaceModel_<curvature>     the Newton model of one face-box-corner gap
//                                term (core/term_hessian.h): analytic curvature
//                                (contact/distance_hessian.h) or central
//                                differences of its Jacobian
//   build_bench/bench/micro_benchmarks --benchmark_filter=Term
#include <memory>

#include <benchmark/benchmark.h>
#include <ceres/autodiff_cost_function.h>

#include "contact/barrier.h"
#include "contact/contact_terms.h"
#include "contact/obstacles/box_obstacle.h"
#include "core/term_hessian.h"
#include "energies/gravity_potential.h"
#include "energies/hookean_spring.h"
#include "energies/inertia.h"
#include "energies/quartic_spring.h"
#include "energies/rayleigh_mass_damping.h"
#include "energies/rayleigh_stiffness_damping.h"
#include "energies/squared_strain_spring.h"
#include "problems/scene_loader.h"
#include "sim/simulation.h"
#include "solver/projected_newton_solver.h"

namespace ipstep {
namespace {

constexpr double kGravity2d[2] = {0.0, -9.81};

// A step context with a predictor and velocity map for 2 nodes.
StepContext* SharedContext(int dim) {
  static StepContext contexts[2];
  StepContext* c = &contexts[dim - 2];
  if (c->x_tilde.size() == 0) {
    c->Resize(dim, 2);
    c->x_tilde.setConstant(0.1);
    c->x_base.setConstant(0.05);
    c->v_base.setConstant(0.2);
    c->x_start.setZero();
    c->x_start[dim] = 1.0;
    c->velocity_slope = 60.0;
  }
  return c;
}

void EvaluateLoop(benchmark::State& bench, const ceres::CostFunction& cost, int dim) {
  const int blocks = static_cast<int>(cost.parameter_block_sizes().size());
  double x[2][3] = {{0.01, -0.02, 0.03}, {1.1, 0.05, -0.04}};
  const double* parameters[2] = {x[0], x[1]};
  double residuals[3];
  double jacobian_storage[2][9];
  double* jacobians[2] = {jacobian_storage[0], jacobian_storage[1]};
  for (auto _ : bench) {
    benchmark::DoNotOptimize(cost.Evaluate(parameters, residuals, jacobians));
    benchmark::ClobberMemory();
  }
  bench.SetLabel(std::to_string(blocks) + " node(s), " + std::to_string(dim) + "D");
}

template <template <int> class Functor, int kResiduals, int kDim, int kNodes, typename... Args>
void BM_Term(benchmark::State& bench, Args... args) {
  std::unique_ptr<ceres::CostFunction> cost;
  if constexpr (kNodes == 1) {
    cost = std::make_unique<ceres::AutoDiffCostFunction<Functor<kDim>, kResiduals, kDim>>(
        new Functor<kDim>(args...));
  } else {
    cost = std::make_unique<ceres::AutoDiffCostFunction<Functor<kDim>, kResiduals, kDim, kDim>>(
        new Functor<kDim>(args...));
  }
  EvaluateLoop(bench, *cost, kDim);
}

const StepContext* Context2d() { return SharedContext(2); }

void BM_Term_hookean_2d(benchmark::State& b) { BM_Term<HookeanSpring, 1, 2, 2>(b, 1e4, 1.0); }
void BM_Term_hookean_3d(benchmark::State& b) { BM_Term<HookeanSpring, 1, 3, 2>(b, 1e4, 1.0); }
void BM_Term_squared_strain_2d(benchmark::State& b) {
  BM_Term<SquaredStrainSpring, 1, 2, 2>(b, 1e4, 1.0);
}
void BM_Term_quartic_2d(benchmark::State& b) { BM_Term<QuarticSpring, 1, 2, 2>(b, 1.0, 1.0); }
void BM_Term_inertia_2d(benchmark::State& b) {
  BM_Term<InertiaResidual, 2, 2, 1>(b, Context2d(), 0, 1.0);
}
void BM_Term_inertia_3d(benchmark::State& b) {
  BM_Term<InertiaResidual, 3, 3, 1>(b, static_cast<const StepContext*>(SharedContext(3)), 0, 1.0);
}
void BM_Term_mass_damping_2d(benchmark::State& b) {
  BM_Term<RayleighMassDamping, 2, 2, 1>(b, Context2d(), 0, 0.5);
}
void BM_Term_stiffness_damping_2d(benchmark::State& b) {
  BM_Term<RayleighStiffnessDamping, 1, 2, 2>(b, Context2d(), 0, 1, 10.0);
}
void BM_Term_gravity_quasi_static_2d(benchmark::State& b) {
  BM_Term<GravityPotential, 1, 2, 1>(b, Context2d(), 0, 1.0, kGravity2d, 10.0);
}
BENCHMARK(BM_Term_hookean_2d);
BENCHMARK(BM_Term_hookean_3d);
BENCHMARK(BM_Term_squared_strain_2d);
BENCHMARK(BM_Term_quartic_2d);
BENCHMARK(BM_Term_inertia_2d);
BENCHMARK(BM_Term_inertia_3d);
BENCHMARK(BM_Term_mass_damping_2d);
BENCHMARK(BM_Term_stiffness_damping_2d);
BENCHMARK(BM_Term_gravity_quasi_static_2d);

// How a spring's Newton model is built: 0 analytic curvature over d (the
// default), 1 central differences over d, 2 central differences over all
// 2 x dimension parameters.
template <int kDim>
void BM_TermModel_hookean(benchmark::State& bench) {
  Term term;
  term.cost = std::make_unique<ceres::AutoDiffCostFunction<HookeanSpring<kDim>, 1, kDim, kDim>>(
      new HookeanSpring<kDim>(1e4, 1.0));
  term.nodes = {0, 1};
  const HookeanSpring<kDim> spring(1e4, 1.0);
  const int how = static_cast<int>(bench.range(0));
  term.pair_difference = how < 2;
  if (how == 0) {
    term.curvature = [spring](const double* const* x, const double* c, double* curvature) {
      return spring.ResidualCurvature(x, c, curvature);
    };
  }
  double x[2][3] = {{0.01, -0.02, 0.03}, {0.9, 0.05, -0.04}};  // compressed: projected
  const double* parameters[2] = {x[0], x[1]};
  TermModelEvaluator evaluator;
  TermModel model;
  ProjectedHessian projected;
  for (auto _ : bench) {
    benchmark::DoNotOptimize(evaluator.Evaluate(term, kDim, 1.0, parameters, true, &model));
    ProjectHessian(model, &projected);
    benchmark::DoNotOptimize(projected.values.data());
    benchmark::ClobberMemory();
  }
  const char* labels[3] = {"analytic over d", "differences over d", "differences, 2 nodes"};
  bench.SetLabel(labels[how]);
}
BENCHMARK(BM_TermModel_hookean<2>)->DenseRange(0, 2);
BENCHMARK(BM_TermModel_hookean<3>)->DenseRange(0, 2);

// A backward-Euler cloth of n x n nodes at the start of its first step (the
// integrator's predictor set, x at the initial guess), with mutable access to
// the potential.
struct ClothStep {
  explicit ClothStep(int n, Optimizer optimizer = Optimizer::kNewton, int max_iterations = 0) {
    SceneLoadOptions load;
    load.grid_size = n;
    SimulationOptions options;
    options.integrator.name = "backward_euler";
    options.optimizer.optimizer = optimizer;
    options.optimizer.max_iterations = max_iterations;
    sim = std::make_unique<Simulation>(LoadScene("cloth", load), options);
    sim->ReplaceStepSolver([&](IncrementalPotential* p, const State* s) {
      potential = p;
      return MakeStepSolver(p, s, options.optimizer);
    });
    sim->variational_integrator()->Predict(sim->state(), sim->gravity(), sim->time_step(),
                                           &potential->context(), &start);
    sim->state().PrescribedPositions(sim->time_step(), &start);  // pinned nodes stay
  }
  std::unique_ptr<Simulation> sim;
  IncrementalPotential* potential = nullptr;
  Eigen::VectorXd start;
};

void ClothArguments(benchmark::internal::Benchmark* b) {
  for (int n : {20, 60, 100}) b->Arg(n);
  b->Unit(benchmark::kMillisecond);
}

void BM_EnergyGradient(benchmark::State& bench) {
  ClothStep cloth(static_cast<int>(bench.range(0)));
  Eigen::VectorXd gradient(cloth.start.size());
  double energy = 0.0;
  for (auto _ : bench) {
    benchmark::DoNotOptimize(
        cloth.potential->Evaluate(cloth.start.data(), &energy, gradient.data()));
  }
  bench.counters["dofs"] = static_cast<double>(cloth.start.size());
  bench.counters["terms"] = static_cast<double>(cloth.potential->terms().size());
}
BENCHMARK(BM_EnergyGradient)->Apply(ClothArguments);

void BM_ReferenceHessian(benchmark::State& bench) {
  ClothStep cloth(static_cast<int>(bench.range(0)));
  ProjectedNewtonSolver solver(cloth.potential, &cloth.sim->state(), OptimizerOptions());
  for (auto _ : bench) benchmark::DoNotOptimize(solver.AssembleHessian(cloth.start));
  bench.counters["nonzeros"] = static_cast<double>(solver.hessian().nonZeros());
}
BENCHMARK(BM_ReferenceHessian)->Apply(ClothArguments);

// One iteration: a solve capped at one Newton iteration from the step's start.
// Ceres's time includes its per-solve preprocessing (part of every step).
void BM_NewtonIteration_Ceres(benchmark::State& bench) {
  ClothStep cloth(static_cast<int>(bench.range(0)));
  OptimizerOptions options;
  options.optimizer = Optimizer::kNewton;
  options.max_iterations = 1;
  auto solver = MakeStepSolver(cloth.potential, &cloth.sim->state(), options);
  Eigen::VectorXd x;
  for (auto _ : bench) {
    x = cloth.start;
    benchmark::DoNotOptimize(solver->Solve(&x).iterations);
  }
}
BENCHMARK(BM_NewtonIteration_Ceres)->Apply(ClothArguments);

void BM_NewtonIteration_Reference(benchmark::State& bench) {
  ClothStep cloth(static_cast<int>(bench.range(0)));
  OptimizerOptions options;
  options.optimizer = Optimizer::kProjectedNewton;
  options.max_iterations = 1;
  ProjectedNewtonSolver solver(cloth.potential, &cloth.sim->state(), options);
  Eigen::VectorXd x;
  for (auto _ : bench) {
    x = cloth.start;
    benchmark::DoNotOptimize(solver.Solve(&x).iterations);
  }
}
BENCHMARK(BM_NewtonIteration_Reference)->Apply(ClothArguments);

// A triangle 1 mm above a box corner (d_hat 5 mm), closest point interior.
void FaceModel(benchmark::State& bench, bool analytic) {
  static const double kappa = 1e5, time = 0.0;
  const BoxObstacle box(3, Eigen::Vector3d(-0.2, -0.3, -0.2), Eigen::Vector3d(0.2, 0.0, 0.2));
  const int corner = 7;  // upper in every axis
  auto gap = std::make_unique<FaceObstacleGap>(&box, corner, &time, 5e-3, 1e-9);
  Term term;
  term.nodes = {0, 1, 2};
  if (analytic) term.curvature = GapCurvature(gap.get());
  term.cost = std::move(gap);
  term.loss = std::make_unique<BarrierLoss>(5e-3, 1e-4, &kappa);
  const double x[3][3] = {{0.15, 0.001, 0.17}, {0.25, 0.0015, 0.18}, {0.2, 0.0012, 0.26}};
  const double* parameters[3] = {x[0], x[1], x[2]};
  TermModelEvaluator evaluator;
  TermModel model;
  if (!evaluator.Evaluate(term, 3, 1.0, parameters, true, &model) || model.curvature_dropped) {
    bench.SkipWithError("the face term's model failed");
    return;
  }
  for (auto _ : bench) {
    benchmark::DoNotOptimize(evaluator.Evaluate(term, 3, 1.0, parameters, true, &model));
    benchmark::ClobberMemory();
  }
}
void BM_FaceModel_analytic(benchmark::State& b) { FaceModel(b, true); }
void BM_FaceModel_differences(benchmark::State& b) { FaceModel(b, false); }
BENCHMARK(BM_FaceModel_analytic);
BENCHMARK(BM_FaceModel_differences);

}  // namespace
}  // namespace ipstep

BENCHMARK_MAIN();
