// Google Benchmark micro-benchmarks of one elastic element's Newton model
// (docs/benchmarks.md, "Elastic solids"): the time per element and per Newton
// iteration that core/term_hessian.h spends on a triangle (2D) or a
// tetrahedron (3D), for every model, with its analytic curvature
// (energies/elasticity/element_curvature.h) or with central differences of
// the autodiff Jacobian (the curvature callback removed):
//   BM_ElementModel/<dim>/<model>/<analytic>          value, gradient, Hessian
//   BM_ElementProjected/<dim>/<model>/<analytic>      the same + its projection
//                                                     (eigen-decomposition)
//   BM_ElementResidual/<dim>/<model>                  residual + Jacobian only
// and for the tetrahedron the eigensystem of the Hessian, analytic
// (energies/elasticity/isotropic_eigensystem.h: SVD, psi, stress and the
// F-space eigensystem, from F) against Eigen::SelfAdjointEigenSolver of the
// ready-made 9 x 9 F-space Hessian and 12 x 12 element Hessian (the solve
// only, not the Hessian it takes):
//   BM_AnalyticEigensystem/<model>, BM_FSpaceEigenSolver/<model>,
//   BM_ElementEigenSolver/<model>                     models 1, 2, 3
// models: 0 linear, 1 stvk, 2 fixed_corotated, 3 neo_hookean.
//   build/bench/elasticity_micro_benchmarks --benchmark_min_time=0.2
#include <string>

#include <benchmark/benchmark.h>
#include <Eigen/Eigenvalues>

#include "core/term_hessian.h"
#include "energies/elasticity/elasticity_effect.h"
#include "energies/elasticity/isotropic_eigensystem.h"

namespace ipstep {
namespace {

constexpr ElasticModel kModels[] = {ElasticModel::kLinear, ElasticModel::kStvk,
                                    ElasticModel::kFixedCorotated, ElasticModel::kNeoHookean};

// A generic rest simplex, and a compressed, sheared current one.
constexpr double kRest2[3][2] = {{0.1, -0.2}, {1.3, 0.1}, {0.4, 0.9}};
constexpr double kRest3[4][3] = {
    {0.1, -0.2, 0.05}, {1.2, 0.1, -0.1}, {0.3, 1.1, 0.2}, {0.2, 0.3, 0.95}};
constexpr double kNow2[3][2] = {{0.12, -0.19}, {1.1, 0.15}, {0.5, 0.7}};
constexpr double kNow3[4][3] = {
    {0.1, -0.2, 0.05}, {1.0, 0.2, -0.05}, {0.4, 0.9, 0.25}, {0.2, 0.35, 0.7}};

struct Setup {
  Setup(int dim, int model, bool analytic) : dim(dim) {
    ElasticMaterial material;
    material.model = kModels[model];
    material.youngs_modulus = 1e7;
    material.poisson_ratio = 0.45;
    material.density = 1150.0;
    const double* rest[4];
    for (int a = 0; a <= dim; ++a) {
      rest[a] = dim == 2 ? kRest2[a] : kRest3[a];
      for (int k = 0; k < dim; ++k) x[a][k] = dim == 2 ? kNow2[a][k] : kNow3[a][k];
      parameters[a] = x[a];
    }
    mu = material.mu();
    lambda = material.lambda(dim);
    term = MakeElasticElementTerm(material, dim, rest, {0, 1, 2, 3});
    if (!analytic) term.curvature = nullptr;
    label = std::string(ElasticModelName(material.model)) + (dim == 2 ? " 2D" : " 3D") +
            (term.gauss_newton_model ? ", J^T J exact"
             : term.curvature        ? ", analytic"
                                     : ", differences");
  }
  int dim;
  double mu = 0.0, lambda = 0.0;
  double x[4][3] = {};
  const double* parameters[4] = {};
  Term term;
  std::string label;
};

void BM_ElementModel(benchmark::State& bench) {
  Setup s(static_cast<int>(bench.range(0)), static_cast<int>(bench.range(1)), bench.range(2) != 0);
  TermModelEvaluator evaluator;
  TermModel model;
  if (!evaluator.Evaluate(s.term, s.dim, 1.0, s.parameters, true, &model)) {
    bench.SkipWithError("the element's model failed");
    return;
  }
  for (auto _ : bench) {
    benchmark::DoNotOptimize(evaluator.Evaluate(s.term, s.dim, 1.0, s.parameters, true, &model));
    benchmark::ClobberMemory();
  }
  bench.SetLabel(s.label);
}

void BM_ElementProjected(benchmark::State& bench) {
  Setup s(static_cast<int>(bench.range(0)), static_cast<int>(bench.range(1)), bench.range(2) != 0);
  TermModelEvaluator evaluator;
  TermModel model;
  ProjectedHessian projected;
  if (!evaluator.Evaluate(s.term, s.dim, 1.0, s.parameters, true, &model)) {
    bench.SkipWithError("the element's model failed");
    return;
  }
  for (auto _ : bench) {
    benchmark::DoNotOptimize(evaluator.Evaluate(s.term, s.dim, 1.0, s.parameters, true, &model));
    ProjectHessian(model, &projected);
    benchmark::DoNotOptimize(projected.values.data());
    benchmark::ClobberMemory();
  }
  bench.SetLabel(s.label);
}

void BM_ElementResidual(benchmark::State& bench) {
  Setup s(static_cast<int>(bench.range(0)), static_cast<int>(bench.range(1)), true);
  const int m = s.term.cost->num_residuals();
  double residuals[16];
  double blocks[4][16 * 3];
  double* jacobians[4] = {blocks[0], blocks[1], blocks[2], blocks[3]};
  for (auto _ : bench) {
    benchmark::DoNotOptimize(s.term.cost->Evaluate(s.parameters, residuals, jacobians));
    benchmark::ClobberMemory();
  }
  bench.SetLabel(s.label.substr(0, s.label.find(',')) + ", " + std::to_string(m) + " residuals");
}

// The tetrahedron's F = Ds Dm^{-1}.
Eigen::Matrix3d TetrahedronF() {
  Eigen::Matrix3d ds, dm;
  for (int c = 0; c < 3; ++c) {
    for (int k = 0; k < 3; ++k) {
      ds(k, c) = kNow3[c + 1][k] - kNow3[0][k];
      dm(k, c) = kRest3[c + 1][k] - kRest3[0][k];
    }
  }
  return ds * dm.inverse();
}

void BM_AnalyticEigensystem(benchmark::State& bench) {
  const Setup s(3, static_cast<int>(bench.range(0)), true);
  const Eigen::Matrix3d F = TetrahedronF();
  DeformationModel<3> out;
  for (auto _ : bench) {
    benchmark::DoNotOptimize(
        IsotropicDeformationModel<3>(kModels[bench.range(0)], F, s.mu, s.lambda, true, &out));
    benchmark::DoNotOptimize(out.eigenvectors.data());
    benchmark::ClobberMemory();
  }
  bench.SetLabel(std::string(ElasticModelName(kModels[bench.range(0)])) + " 3D, from F");
}

void BM_FSpaceEigenSolver(benchmark::State& bench) {
  const Setup s(3, static_cast<int>(bench.range(0)), true);
  DeformationModel<3> out;
  if (!IsotropicDeformationModel<3>(kModels[bench.range(0)], TetrahedronF(), s.mu, s.lambda, true,
                                    &out)) {
    bench.SkipWithError("the F-space model failed");
    return;
  }
  const Eigen::Matrix<double, 9, 9> A =
      out.eigenvectors * out.eigenvalues.asDiagonal() * out.eigenvectors.transpose();
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, 9, 9>> solver;
  for (auto _ : bench) {
    solver.compute(A);
    benchmark::DoNotOptimize(solver.eigenvectors().data());
    benchmark::ClobberMemory();
  }
  bench.SetLabel(std::string(ElasticModelName(kModels[bench.range(0)])) + " 3D, 9 x 9");
}

void BM_ElementEigenSolver(benchmark::State& bench) {
  const Setup s(3, static_cast<int>(bench.range(0)), true);
  TermModelEvaluator evaluator;
  TermModel model;
  if (!evaluator.Evaluate(s.term, s.dim, 1.0, s.parameters, true, &model)) {
    bench.SkipWithError("the element's model failed");
    return;
  }
  const Eigen::Matrix<double, 12, 12> H = model.hessian;
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, 12, 12>> solver;
  for (auto _ : bench) {
    solver.compute(H);
    benchmark::DoNotOptimize(solver.eigenvectors().data());
    benchmark::ClobberMemory();
  }
  bench.SetLabel(std::string(ElasticModelName(kModels[bench.range(0)])) + " 3D, 12 x 12");
}

void ModelArguments(benchmark::internal::Benchmark* b) {
  for (int dim : {2, 3}) {
    for (int model = 0; model < 4; ++model) {
      for (int analytic : {1, 0}) b->Args({dim, model, analytic});
    }
  }
}

BENCHMARK(BM_ElementModel)->Apply(ModelArguments);
BENCHMARK(BM_ElementProjected)->Apply(ModelArguments);
BENCHMARK(BM_ElementResidual)->ArgsProduct({{2, 3}, {0, 1, 2, 3}});
BENCHMARK(BM_AnalyticEigensystem)->DenseRange(1, 3);
BENCHMARK(BM_FSpaceEigenSolver)->DenseRange(1, 3);
BENCHMARK(BM_ElementEigenSolver)->DenseRange(1, 3);

}  // namespace
}  // namespace ipstep

BENCHMARK_MAIN();
