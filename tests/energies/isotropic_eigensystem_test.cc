// The analytic F-space eigensystems (energies/elasticity/isotropic_eigensystem.h)
// against the element energies they describe (element_energy.h) and against
// central differences: for neo_hookean, stvk and fixed_corotated in 2D and 3D,
// over random deformation gradients (J from 0.2 to 3), rotations, F = I,
// repeated and nearly repeated singular values, strong compression and large
// stretch:
//   psi = the element's 1/2 rho(|r|^2) / V (unit reference simplex, Dm = I),
//   stress = central differences of that energy,
//   Q diag(l) Q^T = central differences of the stress, Q orthonormal, and the
//   sorted l = Eigen::SelfAdjointEigenSolver on that Hessian;
// and mapped to an element's coordinates (generic Dm), the gradient and Newton
// Hessian of the term the simulation uses (core/term_hessian.h).
#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <Eigen/Dense>

#include "core/term_hessian.h"
#include "energies/elasticity/elasticity_effect.h"
#include "energies/elasticity/element_energy.h"
#include "energies/elasticity/isotropic_eigensystem.h"

namespace ipstep {
namespace {

constexpr ElasticModel kIsotropicModels[] = {ElasticModel::kNeoHookean, ElasticModel::kStvk,
                                             ElasticModel::kFixedCorotated};

struct Lame {
  double mu, lambda;
};
// nu = 0.3 and nu = 0.48 (lambda / mu = 2.3 and 24.7).
constexpr Lame kMaterials[] = {{1.0, 2.3}, {0.7, 17.3}};

template <int d>
using Mat = Eigen::Matrix<double, d, d>;
template <int d>
using Vec = Eigen::Matrix<double, d, 1>;
template <int d>
using FVec = Eigen::Matrix<double, d * d, 1>;
template <int d>
using FMat = Eigen::Matrix<double, d * d, d * d>;

// vec(M)[i d + j] = M(i, j).
template <int d>
FVec<d> Vectorize(const Mat<d>& M) {
  FVec<d> v;
  for (int i = 0; i < d; ++i) {
    for (int j = 0; j < d; ++j) v[i * d + j] = M(i, j);
  }
  return v;
}
// ---- Deformation gradients -------------------------------------------------

template <int d>
Mat<d> RandomRotation(std::mt19937& rng) {
  std::normal_distribution<double> normal;
  Mat<d> A;
  for (int i = 0; i < d; ++i) {
    for (int j = 0; j < d; ++j) A(i, j) = normal(rng);
  }
  Mat<d> Q = Eigen::HouseholderQR<Mat<d>>(A).householderQ();
  if (Q.determinant() < 0.0) Q.col(0) *= -1.0;
  return Q;
}

template <int d>
struct Case {
  std::string name;
  Mat<d> F;
};

template <int d>
std::vector<Case<d>> Cases() {
  std::mt19937 rng(2019);
  std::vector<Case<d>> cases;
  const auto with_sigma = [&](const std::string& name, Vec<d> sigma, bool rotated) {
    const Mat<d> S = sigma.asDiagonal();
    cases.push_back(
        {name,
         rotated ? Mat<d>(RandomRotation<d>(rng) * S * RandomRotation<d>(rng).transpose()) : S});
  };
  // Pads a 3D list of singular values to d.
  const auto sv = [](double a, double b, double c) {
    Vec<d> s;
    s[0] = a;
    s[1] = b;
    if constexpr (d == 3) s[2] = c;
    return s;
  };
  cases.push_back({"identity", Mat<d>::Identity()});
  for (int k = 0; k < 4; ++k) cases.push_back({"rotation", RandomRotation<d>(rng)});
  if constexpr (d == 2) {
    cases.push_back({"half turn", -Mat<d>::Identity()});
  } else {
    cases.push_back(
        {"half turn", Eigen::AngleAxisd(M_PI, Eigen::Vector3d(0.6, 0.0, 0.8)).toRotationMatrix()});
  }
  std::uniform_real_distribution<double> log_sigma(-0.8, 0.7);
  while (cases.size() < 35) {
    Vec<d> s;
    for (int k = 0; k < d; ++k) s[k] = std::exp(log_sigma(rng));
    if (s.prod() < 0.2 || s.prod() > 3.0) continue;
    with_sigma("random", s, true);
  }
  std::normal_distribution<double> normal(0.0, 0.5);
  while (cases.size() < 45) {
    Mat<d> F = Mat<d>::Identity();
    for (int i = 0; i < d; ++i) {
      for (int j = 0; j < d; ++j) F(i, j) += normal(rng);
    }
    if (F.determinant() < 0.2 || F.determinant() > 3.0) continue;
    cases.push_back({"random entries", F});
  }
  for (bool rotated : {false, true}) {
    with_sigma("repeated", sv(0.8, 0.8, 1.3), rotated);
    with_sigma("repeated", sv(1.2, 1.2, 0.7), rotated);
    with_sigma("uniform", sv(0.7, 0.7, 0.7), rotated);
    with_sigma("uniform", sv(1.4, 1.4, 1.4), rotated);
    with_sigma("near-repeated", sv(1.1, 1.1 * (1.0 + 1e-9), 0.9), rotated);
    with_sigma("near-repeated", sv(1.0 + 1e-7, 1.0, 1.0 - 1e-7), rotated);
    with_sigma("near-identity", sv(1.0 + 1e-10, 1.0 - 1e-10, 1.0), rotated);
    with_sigma("compression", sv(0.3, 0.4, 0.35), rotated);
    with_sigma("compression", sv(1.0, 0.2, 1.0), rotated);
    with_sigma("stretch", sv(3.0, 1.0, 1.0), rotated);
    with_sigma("stretch", sv(2.5, 2.0, 1.5), rotated);
  }
  Mat<d> shear = Mat<d>::Identity();
  shear(0, 1) = 1.5;
  cases.push_back({"simple shear", shear});
  return cases;
}

// ---- References ------------------------------------------------------------

// 1/2 rho(|r|^2) / V of ElasticElement<kModel, d> on the unit reference simplex
// (Dm = I, so its F is exactly F); NaN where the element fails.
template <ElasticModel kModel, int d>
double ElementDensity(const Mat<d>& F, double mu, double lambda) {
  double rest[d + 1][d] = {};
  double x[d + 1][d] = {};
  const double* rest_nodes[d + 1];
  const double* nodes[d + 1];
  for (int a = 0; a <= d; ++a) {
    if (a > 0) rest[a][a - 1] = 1.0;
    for (int k = 0; k < d && a > 0; ++k) x[a][k] = F(k, a - 1);
    rest_nodes[a] = rest[a];
    nodes[a] = x[a];
  }
  const ElasticElement<kModel, d> element(rest_nodes, mu, lambda);
  double r[ElasticElement<kModel, d>::kResiduals];
  if (!element.Residuals(nodes, r)) return std::numeric_limits<double>::quiet_NaN();
  double s = 0.0;
  for (double v : r) s += v * v;
  // neo_hookean's loss rho(s) = s - c (element_energy.h).
  if (kModel == ElasticModel::kNeoHookean) s -= element.offset;
  return 0.5 * s / element.volume;
}

template <int d>
double ElementDensity(ElasticModel model, const Mat<d>& F, const Lame& m) {
  switch (model) {
    case ElasticModel::kNeoHookean:
      return ElementDensity<ElasticModel::kNeoHookean, d>(F, m.mu, m.lambda);
    case ElasticModel::kStvk:
      return ElementDensity<ElasticModel::kStvk, d>(F, m.mu, m.lambda);
    case ElasticModel::kFixedCorotated:
      return ElementDensity<ElasticModel::kFixedCorotated, d>(F, m.mu, m.lambda);
    default:
      return std::numeric_limits<double>::quiet_NaN();
  }
}

// Central-difference step for entries of F: small against the smallest
// singular value (the derivatives of neo_hookean grow as its inverse powers).
template <int d>
double Step(const Mat<d>& F) {
  return 1e-5 * Eigen::JacobiSVD<Mat<d>>(F).singularValues().minCoeff();
}

template <int d>
FVec<d> StressByDifferences(ElasticModel model, const Mat<d>& F, const Lame& m) {
  const double h = Step<d>(F);
  FVec<d> g;
  for (int k = 0; k < d * d; ++k) {
    Mat<d> plus = F, minus = F;
    plus(k / d, k % d) += h;
    minus(k / d, k % d) -= h;
    g[k] = (ElementDensity<d>(model, plus, m) - ElementDensity<d>(model, minus, m)) / (2.0 * h);
  }
  return g;
}

// Central differences of the stress, symmetrised; false if a side fails.
template <int d>
bool HessianByDifferences(ElasticModel model, const Mat<d>& F, const Lame& m, FMat<d>* A) {
  const double h = Step<d>(F);
  for (int k = 0; k < d * d; ++k) {
    Mat<d> plus = F, minus = F;
    plus(k / d, k % d) += h;
    minus(k / d, k % d) -= h;
    DeformationModel<d> p, q;
    if (!IsotropicDeformationModel<d>(model, plus, m.mu, m.lambda, false, &p) ||
        !IsotropicDeformationModel<d>(model, minus, m.mu, m.lambda, false, &q)) {
      return false;
    }
    A->col(k) = (p.stress - q.stress) / (2.0 * h);
  }
  *A = 0.5 * (*A + A->transpose()).eval();
  return true;
}

std::string Label(ElasticModel model, int d, const std::string& name, int index) {
  return std::string(ElasticModelName(model)) + " " + std::to_string(d) + "D " + name + " #" +
         std::to_string(index);
}

// ---- The model against the element and central differences -----------------

template <int d>
void CheckAgainstDifferences() {
  const std::vector<Case<d>> cases = Cases<d>();
  for (ElasticModel model : kIsotropicModels) {
    for (const Lame& m : kMaterials) {
      for (size_t c = 0; c < cases.size(); ++c) {
        const Mat<d>& F = cases[c].F;
        const std::string label = Label(model, d, cases[c].name, static_cast<int>(c));
        DeformationModel<d> out, value_only;
        ASSERT_TRUE(IsotropicDeformationModel<d>(model, F, m.mu, m.lambda, true, &out)) << label;
        ASSERT_TRUE(IsotropicDeformationModel<d>(model, F, m.mu, m.lambda, false, &value_only))
            << label;
        EXPECT_EQ(value_only.psi, out.psi) << label;
        EXPECT_EQ(value_only.stress, out.stress) << label;

        // 1. psi and the stress.
        const double psi = ElementDensity<d>(model, F, m);
        EXPECT_NEAR(out.psi, psi, 1e-12 * (std::abs(psi) + m.mu)) << label;
        const FVec<d> stress = StressByDifferences<d>(model, F, m);
        EXPECT_LE((out.stress - stress).cwiseAbs().maxCoeff(),
                  1e-6 * (stress.cwiseAbs().maxCoeff() + m.mu))
            << label << "\n analytic " << out.stress.transpose() << "\n differences "
            << stress.transpose();

        // 2. The eigensystem.
        FMat<d> A;
        ASSERT_TRUE(HessianByDifferences<d>(model, F, m, &A)) << label;
        const FMat<d>& Q = out.eigenvectors;
        const FMat<d> rebuilt = Q * out.eigenvalues.asDiagonal() * Q.transpose();
        const double scale = A.cwiseAbs().maxCoeff();
        EXPECT_LE((rebuilt - A).cwiseAbs().maxCoeff(), 1e-6 * scale)
            << label << "\n analytic\n"
            << rebuilt << "\n differences\n"
            << A;
        EXPECT_LE((Q.transpose() * Q - FMat<d>::Identity()).cwiseAbs().maxCoeff(), 1e-12) << label;
        Eigen::SelfAdjointEigenSolver<FMat<d>> reference(A);
        FVec<d> sorted = out.eigenvalues;
        std::sort(sorted.data(), sorted.data() + d * d);
        EXPECT_LE((sorted - reference.eigenvalues()).cwiseAbs().maxCoeff(), 1e-6 * scale)
            << label << "\n analytic " << sorted.transpose() << "\n reference "
            << reference.eigenvalues().transpose();
      }
    }
  }
}

TEST(IsotropicEigensystem, MatchesTheElementEnergyAndDifferences2D) {
  CheckAgainstDifferences<2>();
}
TEST(IsotropicEigensystem, MatchesTheElementEnergyAndDifferences3D) {
  CheckAgainstDifferences<3>();
}

// ---- Exact values where the formulas would divide by zero ------------------

// At rest (and on the rotations) every model is linear elasticity: the
// rotations (twists) cost 0, the deviatoric modes 2 mu, the dilation
// 2 mu + d lambda; every entry finite, Q orthonormal.
template <int d>
void CheckRestAndRotations() {
  std::mt19937 rng(5);
  for (ElasticModel model : kIsotropicModels) {
    for (int k = 0; k < 5; ++k) {
      const Mat<d> F = k == 0 ? Mat<d>::Identity() : RandomRotation<d>(rng);
      const std::string label = Label(model, d, k == 0 ? "identity" : "rotation", k);
      const Lame& m = kMaterials[0];
      DeformationModel<d> out;
      ASSERT_TRUE(IsotropicDeformationModel<d>(model, F, m.mu, m.lambda, true, &out)) << label;
      EXPECT_TRUE(out.eigenvectors.allFinite()) << label;
      EXPECT_NEAR(out.psi, 0.0, 1e-14) << label;
      EXPECT_LE(out.stress.cwiseAbs().maxCoeff(), 1e-14) << label;
      FVec<d> expected;
      for (int i = 0; i < d * (d - 1) / 2; ++i) expected[i] = 0.0;
      for (int i = d * (d - 1) / 2; i < d * d - 1; ++i) expected[i] = 2.0 * m.mu;
      expected[d * d - 1] = 2.0 * m.mu + d * m.lambda;
      FVec<d> sorted = out.eigenvalues;
      std::sort(sorted.data(), sorted.data() + d * d);
      EXPECT_LE((sorted - expected).cwiseAbs().maxCoeff(), 1e-13) << label << "\n"
                                                                  << sorted.transpose();
      // The dilation mode is vec(F) / sqrt(d) (F = R: R scaled uniformly).
      int dilation = 0;
      out.eigenvalues.maxCoeff(&dilation);
      EXPECT_NEAR(std::abs(out.eigenvectors.col(dilation).dot(Vectorize<d>(F))), std::sqrt(d),
                  1e-13)
          << label;
    }
  }
}

TEST(IsotropicEigensystem, RestAndRotationsAreLinearElasticity) {
  CheckRestAndRotations<2>();
  CheckRestAndRotations<3>();
}

// Exactly repeated singular values, F = diag(a, a, b): finite, and the pair
// (0, 1)'s flip e_0 e_1^T + e_1 e_0^T and the scaling mode diag(1, -1, 0)
// are eigenvectors of one eigenvalue (the flip's limit Psi_00 - Psi_01),
// which for neo_hookean is mu + (mu - lambda ln J) / a^2.
TEST(IsotropicEigensystem, RepeatedSingularValuesAreExact) {
  const double mu = 1.0, lambda = 2.3;
  for (ElasticModel model : kIsotropicModels) {
    for (double a : {0.5, 1.0, 1.7}) {
      for (double b : {0.6, 1.0, 2.2}) {
        const std::string label = std::string(ElasticModelName(model)) + " a " + std::to_string(a) +
                                  " b " + std::to_string(b);
        const Eigen::Matrix3d F = Eigen::Vector3d(a, a, b).asDiagonal();
        DeformationModel<3> out;
        ASSERT_TRUE(IsotropicDeformationModel<3>(model, F, mu, lambda, true, &out)) << label;
        ASSERT_TRUE(out.eigenvalues.allFinite() && out.eigenvectors.allFinite()) << label;
        EXPECT_TRUE(std::isfinite(out.psi) && out.stress.allFinite()) << label;
        const FMat<3> A =
            out.eigenvectors * out.eigenvalues.asDiagonal() * out.eigenvectors.transpose();
        FVec<3> flip = FVec<3>::Zero(), scaling = FVec<3>::Zero();
        flip[1] = flip[3] = std::sqrt(0.5);
        scaling[0] = std::sqrt(0.5);
        scaling[4] = -std::sqrt(0.5);
        const double l = flip.dot(A * flip);
        EXPECT_LE((A * flip - l * flip).norm(), 1e-12 * A.norm()) << label;
        EXPECT_LE((A * scaling - l * scaling).norm(), 1e-12 * A.norm()) << label;
        if (model == ElasticModel::kNeoHookean) {
          EXPECT_NEAR(l, mu + (mu - lambda * std::log(a * a * b)) / (a * a), 1e-12 * A.norm())
              << label;
        }
        const Eigen::Matrix2d F2 = Eigen::Vector2d(a, a).asDiagonal();
        DeformationModel<2> out2;
        ASSERT_TRUE(IsotropicDeformationModel<2>(model, F2, mu, lambda, true, &out2)) << label;
        EXPECT_TRUE(out2.eigenvalues.allFinite() && out2.eigenvectors.allFinite()) << label;
      }
    }
  }
}

// ---- Outside the domain ----------------------------------------------------

TEST(IsotropicEigensystem, FailsWhereJIsNotPositive) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  Eigen::Matrix3d inverted;
  inverted << 1.1, 0.2, -0.1, 0.05, 0.9, 0.25, -0.2, 0.1, -1.3;
  const Eigen::Matrix3d bad[] = {Eigen::Vector3d(1.0, 1.0, -1.0).asDiagonal(),
                                 Eigen::Vector3d(1.0, 1.0, 0.0).asDiagonal(),
                                 Eigen::Matrix3d::Zero(),
                                 -Eigen::Matrix3d::Identity(),
                                 inverted,
                                 Eigen::Vector3d(1.0, nan, 1.0).asDiagonal()};
  for (ElasticModel model : kIsotropicModels) {
    for (const Eigen::Matrix3d& F : bad) {
      DeformationModel<3> out;
      EXPECT_FALSE(IsotropicDeformationModel<3>(model, F, 1.0, 2.3, true, &out))
          << ElasticModelName(model) << "\n"
          << F;
      EXPECT_FALSE(IsotropicDeformationModel<3>(model, F, 1.0, 2.3, false, &out));
    }
    DeformationModel<2> out2;
    const Eigen::Matrix2d reflection = Eigen::Vector2d(1.0, -1.0).asDiagonal();
    EXPECT_FALSE(IsotropicDeformationModel<2>(model, reflection, 1.0, 2.3, true, &out2));
    EXPECT_FALSE(
        IsotropicDeformationModel<2>(model, Eigen::Matrix2d::Zero(), 1.0, 2.3, true, &out2));
  }
  // linear is not isotropic (not handled).
  DeformationModel<3> out;
  EXPECT_FALSE(IsotropicDeformationModel<3>(ElasticModel::kLinear, Eigen::Matrix3d::Identity(), 1.0,
                                            2.3, true, &out));
}

// ---- Mapped to an element: the simulation's term ---------------------------

// grad e = V B^T vec(P) and Hess e = V B^T A B with B = d vec(F) / dx
// (element_curvature.h's (1)), on a generic rest simplex, against
// TermModelEvaluator on MakeElasticElementTerm (the Newton model the solvers
// use: analytic curvature, or central differences for 3D fixed_corotated).
template <int d>
void CheckElementModel() {
  const std::vector<double> rest =
      d == 2 ? std::vector<double>{0.1, -0.2, 1.3, 0.1, 0.4, 0.9}
             : std::vector<double>{0.1, -0.2, 0.05, 1.2, 0.1, -0.1, 0.3, 1.1, 0.2, 0.2, 0.3, 0.95};
  constexpr int n = (d + 1) * d;
  Mat<d> Dm;
  for (int c = 0; c < d; ++c) {
    for (int k = 0; k < d; ++k) Dm(k, c) = rest[d * (c + 1) + k] - rest[k];
  }
  const double volume = Dm.determinant() / (d == 2 ? 2.0 : 6.0);
  const Mat<d> dm_inv = Dm.inverse();
  // B[(i d + j), (a d + i)] = D_aj, D_a = row a - 1 of Dm^{-1}, D_0 = -sum.
  Eigen::Matrix<double, d * d, n> B = Eigen::Matrix<double, d * d, n>::Zero();
  for (int a = 0; a <= d; ++a) {
    for (int i = 0; i < d; ++i) {
      for (int j = 0; j < d; ++j) {
        const double D = a == 0 ? -dm_inv.col(j).sum() : dm_inv(a - 1, j);
        B(i * d + j, a * d + i) = D;
      }
    }
  }
  Mat<d> F;
  if constexpr (d == 2) {
    F << 1.2, 0.3, -0.15, 0.85;
  } else {
    F << 1.1, 0.2, -0.1, 0.05, 0.9, 0.25, -0.2, 0.1, 1.3;
  }
  std::vector<double> x(n);
  const double* rest_nodes[4];
  const double* nodes[4];
  for (int a = 0; a <= d; ++a) {
    const Vec<d> X = Eigen::Map<const Vec<d>>(rest.data() + d * a);
    Eigen::Map<Vec<d>>(x.data() + d * a) = F * X + Vec<d>::Constant(0.37);
    rest_nodes[a] = rest.data() + d * a;
    nodes[a] = x.data() + d * a;
  }
  for (ElasticModel model : kIsotropicModels) {
    ElasticMaterial material;
    material.model = model;
    material.youngs_modulus = 2.6;
    material.poisson_ratio = 0.3;
    const double mu = material.mu(), lambda = material.lambda(d);
    const Term term = MakeElasticElementTerm(material, d, rest_nodes, {0, 1, 2, 3});
    TermModelEvaluator evaluator;
    TermModel reference;
    ASSERT_TRUE(evaluator.Evaluate(term, d, 1.0, nodes, true, &reference));
    DeformationModel<d> out;
    ASSERT_TRUE(IsotropicDeformationModel<d>(model, F, mu, lambda, true, &out));
    const std::string label = Label(model, d, "element", 0);
    EXPECT_NEAR(volume * out.psi, reference.energy, 1e-12 * mu * volume) << label;
    const Eigen::Matrix<double, n, 1> gradient = volume * B.transpose() * out.stress;
    EXPECT_LE((gradient - reference.gradient).cwiseAbs().maxCoeff(), 1e-10 * mu) << label;
    const Eigen::Matrix<double, n, n> hessian = volume * B.transpose() * out.eigenvectors *
                                                out.eigenvalues.asDiagonal() *
                                                out.eigenvectors.transpose() * B;
    EXPECT_LE((hessian - reference.hessian).cwiseAbs().maxCoeff(),
              1e-6 * reference.hessian.cwiseAbs().maxCoeff())
        << label << "\n"
        << hessian << "\n"
        << reference.hessian;
  }
}

TEST(IsotropicEigensystem, MappedToAnElementGivesTheTermsNewtonModel) {
  CheckElementModel<2>();
  CheckElementModel<3>();
}

}  // namespace
}  // namespace ipstep
