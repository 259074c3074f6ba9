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
// models: 0 linear, 1 stvk, 2 fixed_corotated, 3 neo_hookean.
//   build/bench/elasticity_micro_benchmarks --benchmark_min_time=0.2
#include <string>

#include <benchmark/benchmark.h>

#include "core/term_hessian.h"
#include "energies/elasticity/elasticity_effect.h"

namespace ipstep {
namespace {

constexpr ElasticModel kModels[] = {ElasticModel::kLinear, ElasticModel::kStvk,
                                    ElasticModel::kFixedCorotated, ElasticModel::kNeoHookean};

struct Setup {
  Setup(int dim, int model, bool analytic) : dim(dim) {
    ElasticMaterial material;
    material.model = kModels[model];
    material.youngs_modulus = 1e7;
    material.poisson_ratio = 0.45;
    material.density = 1150.0;
    // A generic rest simplex, and a compressed, sheared current one.
    const double rest2[3][2] = {{0.1, -0.2}, {1.3, 0.1}, {0.4, 0.9}};
    const double rest3[4][3] = {
        {0.1, -0.2, 0.05}, {1.2, 0.1, -0.1}, {0.3, 1.1, 0.2}, {0.2, 0.3, 0.95}};
    const double now2[3][2] = {{0.12, -0.19}, {1.1, 0.15}, {0.5, 0.7}};
    const double now3[4][3] = {
        {0.1, -0.2, 0.05}, {1.0, 0.2, -0.05}, {0.4, 0.9, 0.25}, {0.2, 0.35, 0.7}};
    const double* rest[4];
    for (int a = 0; a <= dim; ++a) {
      rest[a] = dim == 2 ? rest2[a] : rest3[a];
      for (int k = 0; k < dim; ++k) x[a][k] = dim == 2 ? now2[a][k] : now3[a][k];
      parameters[a] = x[a];
    }
    term = MakeElasticElementTerm(material, dim, rest, {0, 1, 2, 3});
    if (!analytic) term.curvature = nullptr;
    label = std::string(ElasticModelName(material.model)) + (dim == 2 ? " 2D" : " 3D") +
            (term.gauss_newton_model ? ", J^T J exact"
             : term.curvature        ? ", analytic"
                                     : ", differences");
  }
  int dim;
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

}  // namespace
}  // namespace ipstep

BENCHMARK_MAIN();
