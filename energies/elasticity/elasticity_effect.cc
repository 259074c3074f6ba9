#include "energies/elasticity/elasticity_effect.h"

#include <memory>
#include <sstream>
#include <utility>

#include <ceres/autodiff_cost_function.h>

#include "core/input_error.h"
#include "energies/elasticity/element_energy.h"
#include "energies/elasticity/inversion_filter.h"
#include "problems/solid.h"

namespace ipstep {
namespace {

// rho(s) = s - c: gives back the energy from the neo-Hookean residual
// r = sqrt(2 e + c) (element_energy.h).
class OffsetLoss : public ceres::LossFunction {
 public:
  explicit OffsetLoss(double offset) : offset_(offset) {}
  void Evaluate(double s, double rho[3]) const override {
    rho[0] = s - offset_;
    rho[1] = 1.0;
    rho[2] = 0.0;
  }

 private:
  double offset_;
};

template <ElasticModel kModel, int kDim>
void FillTerm(const ElasticMaterial& material, const double* const* rest, Term* term) {
  using F = ElasticElement<kModel, kDim>;
  const F functor(rest, material.mu(), material.lambda(kDim));
  if constexpr (kDim == 2) {
    term->cost =
        std::make_unique<ceres::AutoDiffCostFunction<F, F::kResiduals, 2, 2, 2>>(new F(functor));
    term->precise_residual = [functor](const double* const* x, long double* r) {
      long double xl[3][2];
      const long double* p[3];
      for (int a = 0; a < 3; ++a) {
        for (int k = 0; k < 2; ++k) xl[a][k] = x[a][k];
        p[a] = xl[a];
      }
      return functor.Residuals(p, r);
    };
  } else {
    term->cost =
        std::make_unique<ceres::AutoDiffCostFunction<F, F::kResiduals, 3, 3, 3, 3>>(new F(functor));
    term->precise_residual = [functor](const double* const* x, long double* r) {
      long double xl[4][3];
      const long double* p[4];
      for (int a = 0; a < 4; ++a) {
        for (int k = 0; k < 3; ++k) xl[a][k] = x[a][k];
        p[a] = xl[a];
      }
      return functor.Residuals(p, r);
    };
  }
  term->gauss_newton_model = F::kGaussNewtonModel;
  if constexpr (HasAnalyticCurvature(kModel, kDim)) {
    term->curvature = [functor](const double* const* x, const double* c, double* curvature) {
      return functor.Curvature(x, c, curvature);
    };
  }
  if constexpr (HasReducedModel(kModel)) {
    term->reduced_model = [functor](const double* const* x, bool, ReducedModel* model) {
      return functor.FillReducedModel(x, model);
    };
    term->reduced_size = kDim * kDim;
  }
  if constexpr (kModel == ElasticModel::kNeoHookean) {
    term->loss = std::make_unique<OffsetLoss>(functor.offset);
    term->precise_energy = [functor](const double* const* x, long double* energy) {
      return functor.PreciseEnergy(x, energy);
    };
  }
}

template <int kDim>
void FillTermForModel(const ElasticMaterial& material, const double* const* rest, Term* term) {
  switch (material.model) {
    case ElasticModel::kLinear:
      return FillTerm<ElasticModel::kLinear, kDim>(material, rest, term);
    case ElasticModel::kStvk:
      return FillTerm<ElasticModel::kStvk, kDim>(material, rest, term);
    case ElasticModel::kFixedCorotated:
      return FillTerm<ElasticModel::kFixedCorotated, kDim>(material, rest, term);
    case ElasticModel::kNeoHookean:
      return FillTerm<ElasticModel::kNeoHookean, kDim>(material, rest, term);
  }
}

}  // namespace

Term MakeElasticElementTerm(const ElasticMaterial& material, int dimension,
                            const double* const* rest, const std::array<int, 4>& nodes) {
  Term term;
  term.kind = TermKind::kPotential;
  if (dimension == 2) {
    FillTermForModel<2>(material, rest, &term);
  } else {
    FillTermForModel<3>(material, rest, &term);
  }
  term.nodes.assign(nodes.begin(), nodes.begin() + dimension + 1);
  return term;
}

std::string BuildElasticity(TermBuilder& builder, const nlohmann::json& parameters) {
  const Scene& scene = builder.scene();
  if (!parameters.is_null()) {
    throw InputError(scene.source, "elasticity",
                     "takes no parameters: the material is given in \"solid\"");
  }
  if (!scene.solid) {
    throw InputError(scene.source, "effects",
                     "\"elasticity\" needs a \"solid\" (a mesh and its material)");
  }
  const Solid& solid = *scene.solid;
  const SimplexMesh& mesh = solid.mesh;
  const int dim = mesh.dimension;
  auto filter = std::make_unique<InversionFilter>(dim, mesh.elements, mesh.positions);
  const int inverted = filter->FirstInverted(builder.state().x.data());
  if (inverted >= 0) {
    throw InputError(
        scene.source, "solid",
        "element " + std::to_string(inverted) + " is inverted or degenerate in the initial state");
  }
  for (int e = 0; e < mesh.num_elements(); ++e) {
    const double* rest[4];
    for (int a = 0; a <= dim; ++a) rest[a] = mesh.positions.data() + dim * mesh.elements[e][a];
    builder.Add(MakeElasticElementTerm(solid.material, dim, rest, mesh.elements[e]));
  }
  builder.AddStepFilter(std::move(filter));
  std::ostringstream out;
  out << "elasticity: " << mesh.num_elements() << (dim == 2 ? " triangles" : " tetrahedra") << ", "
      << ElasticModelName(solid.material.model) << ", E " << solid.material.youngs_modulus
      << " Pa, nu " << solid.material.poisson_ratio;
  if (dim == 2) out << (solid.material.plane_stress ? ", plane stress" : ", plane strain");
  out << " (" << solid.description << "); inversion filter on";
  return out.str();
}

}  // namespace ipstep
