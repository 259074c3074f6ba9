// Elastic solids (energies/elasticity/): the element energies against their
// formulas (patch test), rotation invariance, derivatives against finite
// differences, the small-strain limit, the inversion filter, the cantilever
// against Euler-Bernoulli beam theory, energy conservation (Newmark) and
// dissipation (backward Euler), and compression without inverted elements.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <Eigen/Dense>
#include <Eigen/SVD>

#include "core/input_error.h"
#include "core/term_hessian.h"
#include "energies/effect_registry.h"
#include "energies/elasticity/elasticity_effect.h"
#include "energies/elasticity/element_curvature.h"
#include "energies/elasticity/inversion_filter.h"
#include "mesh/gmsh_mesh.h"
#include "problems/scene_loader.h"
#include "problems/solid.h"
#include "sim/default_effects.h"
#include "sim/simulation.h"
#include "tests/support/test_scenes.h"

namespace ipstep {
namespace {

using nlohmann::json;
using testing::Options;

constexpr ElasticModel kModels[] = {ElasticModel::kLinear, ElasticModel::kStvk,
                                    ElasticModel::kFixedCorotated, ElasticModel::kNeoHookean};
constexpr ElasticModel kNonlinearModels[] = {ElasticModel::kStvk, ElasticModel::kFixedCorotated,
                                             ElasticModel::kNeoHookean};

ElasticMaterial Material(ElasticModel model, double nu = 0.3) {
  ElasticMaterial m;
  m.model = model;
  m.youngs_modulus = 2e5;
  m.poisson_ratio = nu;
  m.density = 1000.0;
  return m;
}

// Reference energy densities, written independently of element_energy.h with
// Eigen (the rotation of fixed_corotated from an SVD).
double ReferencePsi(const ElasticMaterial& m, int d, const Eigen::MatrixXd& F) {
  const double mu = m.mu(), lambda = m.lambda(d);
  const Eigen::MatrixXd I = Eigen::MatrixXd::Identity(d, d);
  switch (m.model) {
    case ElasticModel::kLinear: {
      const Eigen::MatrixXd eps = 0.5 * (F + F.transpose()) - I;
      return mu * eps.squaredNorm() + 0.5 * lambda * eps.trace() * eps.trace();
    }
    case ElasticModel::kStvk: {
      const Eigen::MatrixXd E = 0.5 * (F.transpose() * F - I);
      return mu * E.squaredNorm() + 0.5 * lambda * E.trace() * E.trace();
    }
    case ElasticModel::kFixedCorotated: {
      Eigen::JacobiSVD<Eigen::MatrixXd> svd(F, Eigen::ComputeFullU | Eigen::ComputeFullV);
      const Eigen::MatrixXd R = svd.matrixU() * svd.matrixV().transpose();  // det F > 0
      const double J = F.determinant();
      return mu * (F - R).squaredNorm() + 0.5 * lambda * (J - 1.0) * (J - 1.0);
    }
    case ElasticModel::kNeoHookean: {
      const double logJ = std::log(F.determinant());
      return 0.5 * mu * (F.squaredNorm() - d) - mu * logJ + 0.5 * lambda * logJ * logJ;
    }
  }
  return 0.0;
}

// A generic (not right-angled) rest simplex, positively oriented.
std::vector<double> RestSimplex(int d) {
  if (d == 2) return {0.1, -0.2, 1.3, 0.1, 0.4, 0.9};
  return {0.1, -0.2, 0.05, 1.2, 0.1, -0.1, 0.3, 1.1, 0.2, 0.2, 0.3, 0.95};
}

double Measure(int d, const std::vector<double>& x) {
  Eigen::MatrixXd D(d, d);
  for (int c = 0; c < d; ++c) {
    for (int k = 0; k < d; ++k) D(k, c) = x[d * (c + 1) + k] - x[k];
  }
  return D.determinant() / (d == 2 ? 2.0 : 6.0);
}

struct Element {
  Element(const ElasticMaterial& material, int d) : d(d), rest(RestSimplex(d)) {
    const double* r[4];
    for (int a = 0; a <= d; ++a) r[a] = rest.data() + d * a;
    term = MakeElasticElementTerm(material, d, r, {0, 1, 2, 3});
  }
  // Energy, and gradient/Hessian over the (d + 1) d coordinates; false
  // outside the domain.
  bool Eval(const std::vector<double>& x, double* energy, Eigen::VectorXd* gradient = nullptr,
            Eigen::MatrixXd* hessian = nullptr) {
    const double* p[4];
    for (int a = 0; a <= d; ++a) p[a] = x.data() + d * a;
    TermModel model;
    if (!evaluator.Evaluate(term, d, 1.0, p, gradient != nullptr, &model)) return false;
    *energy = model.energy;
    if (gradient) *gradient = model.gradient;
    if (hessian) *hessian = model.hessian;
    return true;
  }
  double Energy(const std::vector<double>& x) {
    double e = 0.0;
    EXPECT_TRUE(Eval(x, &e));
    return e;
  }
  // Positions X -> F X + t.
  std::vector<double> Deform(const Eigen::MatrixXd& F) const {
    std::vector<double> x(rest.size());
    for (int a = 0; a <= d; ++a) {
      const Eigen::VectorXd X = Eigen::Map<const Eigen::VectorXd>(rest.data() + d * a, d);
      const Eigen::VectorXd y = F * X + Eigen::VectorXd::Constant(d, 0.37);
      for (int k = 0; k < d; ++k) x[d * a + k] = y[k];
    }
    return x;
  }

  int d;
  std::vector<double> rest;
  Term term;
  TermModelEvaluator evaluator;
};

Eigen::MatrixXd Rotation(int d, double angle) {
  if (d == 2) return Eigen::Rotation2Dd(angle).toRotationMatrix();
  return Eigen::AngleAxisd(angle, Eigen::Vector3d(0.3, -0.5, 0.8).normalized()).toRotationMatrix();
}

Eigen::MatrixXd GenericF(int d) {
  Eigen::MatrixXd F(d, d);
  if (d == 2) {
    F << 1.2, 0.3, -0.15, 0.85;
  } else {
    F << 1.1, 0.2, -0.1, 0.05, 0.9, 0.25, -0.2, 0.1, 1.3;
  }
  return F;
}

// ---- Patch test: affine deformations give exactly V Psi(F) -----------------

TEST(ElasticEnergy, AffineDeformationGivesTheAnalyticEnergy) {
  for (int d : {2, 3}) {
    for (ElasticModel model : kModels) {
      for (bool plane_stress : {false, true}) {
        if (d == 3 && plane_stress) continue;
        ElasticMaterial material = Material(model);
        material.plane_stress = plane_stress;
        Element element(material, d);
        const double V = Measure(d, element.rest);
        for (double scale : {0.5, 1.0, 1.7}) {
          const Eigen::MatrixXd F = Eigen::MatrixXd::Identity(d, d) +
                                    scale * (GenericF(d) - Eigen::MatrixXd::Identity(d, d));
          const double expected = V * ReferencePsi(material, d, F);
          EXPECT_NEAR(element.Energy(element.Deform(F)), expected, 1e-11 * material.mu() * V)
              << ElasticModelName(model) << " " << d << "D scale " << scale;
        }
      }
    }
  }
}

TEST(ElasticEnergy, PlaneStressUsesTheEffectiveLambda) {
  ElasticMaterial m = Material(ElasticModel::kLinear, 0.3);
  m.plane_stress = true;
  // lambda* = E nu / (1 - nu^2).
  EXPECT_NEAR(m.lambda(2), 2e5 * 0.3 / (1.0 - 0.09), 1e-9);
  EXPECT_NEAR(m.lambda(3), 2e5 * 0.3 / (1.3 * 0.4), 1e-9);  // 3D: plane is ignored
}

TEST(ElasticEnergy, RigidMotionsCostNothingForNonlinearModels) {
  for (int d : {2, 3}) {
    for (ElasticModel model : kNonlinearModels) {
      const ElasticMaterial material = Material(model);
      Element element(material, d);
      const double scale = material.mu() * Measure(d, element.rest);
      for (double angle : {0.3, 1.9, 3.0}) {
        const Eigen::MatrixXd R = Rotation(d, angle);
        EXPECT_NEAR(element.Energy(element.Deform(R)), 0.0, 1e-12 * scale)
            << ElasticModelName(model) << " " << d << "D angle " << angle;
        // Frame indifference: Psi(R F) = Psi(F).
        const Eigen::MatrixXd F = GenericF(d);
        EXPECT_NEAR(element.Energy(element.Deform(R * F)), element.Energy(element.Deform(F)),
                    1e-11 * scale)
            << ElasticModelName(model) << " " << d << "D";
      }
    }
    // The linear model is not rotation invariant: a rotation by 0.3 rad costs.
    Element linear(Material(ElasticModel::kLinear), d);
    EXPECT_GT(linear.Energy(linear.Deform(Rotation(d, 0.3))),
              1e-3 * Material(ElasticModel::kLinear).mu());
  }
}

// ---- Derivatives -----------------------------------------------------------

TEST(ElasticEnergy, GradientAndNewtonHessianMatchFiniteDifferences) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> noise(-0.1, 0.1);
  for (int d : {2, 3}) {
    for (ElasticModel model : kModels) {
      Element element(Material(model), d);
      const int n = (d + 1) * d;
      for (int trial = 0; trial < 3; ++trial) {
        std::vector<double> x = element.Deform(GenericF(d));
        for (double& c : x) c += noise(rng);
        double e = 0.0;
        Eigen::VectorXd g;
        Eigen::MatrixXd H;
        ASSERT_TRUE(element.Eval(x, &e, &g, &H));
        const double h = 1e-6;
        Eigen::VectorXd g_fd(n);
        Eigen::MatrixXd H_fd(n, n);
        for (int j = 0; j < n; ++j) {
          std::vector<double> xp = x, xm = x;
          xp[j] += h;
          xm[j] -= h;
          double ep = 0.0, em = 0.0;
          Eigen::VectorXd gp, gm;
          ASSERT_TRUE(element.Eval(xp, &ep, &gp));
          ASSERT_TRUE(element.Eval(xm, &em, &gm));
          g_fd[j] = (ep - em) / (2.0 * h);
          H_fd.col(j) = (gp - gm) / (2.0 * h);
        }
        const std::string what =
            std::string(ElasticModelName(model)) + " " + std::to_string(d) + "D";
        EXPECT_LT((g - g_fd).norm(), 1e-6 * g.norm()) << what;
        EXPECT_LT((H - H_fd).norm(), 1e-5 * H.norm()) << what;
        EXPECT_LT((H - H.transpose()).norm(), 1e-8 * H.norm()) << what;
      }
    }
  }
}

// Deformation gradients for the curvature checks: generic ones, compressed
// ones (J 0.17-0.46, and one flattened to 10 %: J = 0.1), stretched ones
// (J 2.3-3.2) and a sheared one; every det F > 0.
std::vector<Eigen::MatrixXd> CurvatureTestGradients(int d) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> noise(-0.3, 0.3);
  std::vector<Eigen::MatrixXd> out;
  const Eigen::MatrixXd I = Eigen::MatrixXd::Identity(d, d);
  for (double scale : {1.0, 1.0, 1.0, 0.6, 0.45, 1.5}) {
    Eigen::MatrixXd F;
    do {
      F = I;
      for (int i = 0; i < d; ++i) {
        for (int j = 0; j < d; ++j) F(i, j) += noise(rng);
      }
      F *= scale;
    } while (F.determinant() < 0.05);
    out.push_back(F);
  }
  Eigen::MatrixXd squashed = I;
  squashed(d - 1, d - 1) = 0.1;  // flattened to 10 %
  out.push_back(squashed);
  Eigen::MatrixXd sheared = I;
  sheared(0, d - 1) = 2.0;
  out.push_back(Rotation(d, 1.1) * sheared);
  return out;
}

// The analytic ResidualCurvature (element_curvature.h) against central
// differences of the autodiff Jacobian, contracted with random coefficients
// c (not only c = r), and the Newton Hessian it gives against differences of
// the exact gradient and against the model built without it.
TEST(ElasticEnergy, AnalyticCurvatureMatchesFiniteDifferences) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> coefficient(-1.0, 1.0);
  for (int d : {2, 3}) {
    for (ElasticModel model : kModels) {
      for (double nu : {0.3, 0.45}) {
        Element element(Material(model, nu), d);
        const std::string what = std::string(ElasticModelName(model)) + " " + std::to_string(d) +
                                 "D nu " + std::to_string(nu);
        const bool analytic = HasAnalyticCurvature(model, d);
        EXPECT_EQ(static_cast<bool>(element.term.curvature), analytic) << what;
        if (!analytic) continue;
        Element differences(Material(model, nu), d);
        differences.term.curvature = nullptr;  // core/term_hessian.h's central differences
        const int n = (d + 1) * d;
        const int m = element.term.cost->num_residuals();
        int index = 0;
        for (const Eigen::MatrixXd& F : CurvatureTestGradients(d)) {
          const std::string where = what + " F #" + std::to_string(index++);
          std::vector<double> x = element.Deform(F);
          // Residual Jacobian (row-major blocks m x d per node) at x.
          auto jacobian = [&](const std::vector<double>& at, Eigen::MatrixXd* out) {
            const double* p[4];
            std::vector<double> blocks((d + 1) * m * d);
            double* jp[4];
            for (int a = 0; a <= d; ++a) {
              p[a] = at.data() + d * a;
              jp[a] = blocks.data() + a * m * d;
            }
            std::vector<double> r(m);
            if (!element.term.cost->Evaluate(p, r.data(), jp)) return false;
            out->resize(m, n);
            for (int a = 0; a <= d; ++a) {
              for (int row = 0; row < m; ++row) {
                for (int k = 0; k < d; ++k) (*out)(row, a * d + k) = jp[a][row * d + k];
              }
            }
            return true;
          };
          Eigen::VectorXd c(m);
          for (int k = 0; k < m; ++k) c[k] = coefficient(rng);
          const double* p[4];
          for (int a = 0; a <= d; ++a) p[a] = x.data() + d * a;
          Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> C(n, n);
          ASSERT_TRUE(element.term.curvature(p, c.data(), C.data())) << where;
          Eigen::MatrixXd C_fd(n, n);
          for (int j = 0; j < n; ++j) {
            const double h = 1e-6 * std::max(1.0, std::abs(x[j]));
            std::vector<double> xp = x, xm = x;
            xp[j] += h;
            xm[j] -= h;
            Eigen::MatrixXd Jp, Jm;
            ASSERT_TRUE(jacobian(xp, &Jp) && jacobian(xm, &Jm)) << where;
            C_fd.col(j) = (Jp - Jm).transpose() * c / (xp[j] - xm[j]);
          }
          EXPECT_LT((C - C_fd).norm(), 1e-6 * C.norm()) << where;
          EXPECT_LT((C - C.transpose()).norm(), 1e-12 * C.norm()) << where;

          double e = 0.0, e_fd = 0.0;
          Eigen::VectorXd g, g_fd;
          Eigen::MatrixXd H, H_differences;
          ASSERT_TRUE(element.Eval(x, &e, &g, &H)) << where;
          ASSERT_TRUE(differences.Eval(x, &e_fd, &g_fd, &H_differences)) << where;
          EXPECT_LT((H - H_differences).norm(), 1e-6 * H.norm()) << where;
          Eigen::MatrixXd H_fd(n, n);
          for (int j = 0; j < n; ++j) {
            const double h = 1e-6 * std::max(1.0, std::abs(x[j]));
            std::vector<double> xp = x, xm = x;
            xp[j] += h;
            xm[j] -= h;
            double ep = 0.0, em = 0.0;
            Eigen::VectorXd gp, gm;
            ASSERT_TRUE(element.Eval(xp, &ep, &gp) && element.Eval(xm, &em, &gm)) << where;
            H_fd.col(j) = (gp - gm) / (xp[j] - xm[j]);
          }
          EXPECT_LT((H - H_fd).norm(), 1e-6 * H.norm()) << where;
        }
      }
    }
  }
}

// ---- Small-strain limit ----------------------------------------------------

// Psi_model(I + eps G) / Psi_linear(I + eps G) - 1 = O(eps): the energies agree
// to second order in the strain, their difference is O(eps^3).
TEST(ElasticEnergy, NonlinearModelsAgreeWithLinearToSecondOrder) {
  for (int d : {2, 3}) {
    const Eigen::MatrixXd G = GenericF(d) - Eigen::MatrixXd::Identity(d, d);
    Element linear(Material(ElasticModel::kLinear), d);
    for (ElasticModel model : kNonlinearModels) {
      Element element(Material(model), d);
      double previous = 0.0;
      for (double eps : {1e-2, 5e-3, 2.5e-3}) {
        const Eigen::MatrixXd F = Eigen::MatrixXd::Identity(d, d) + eps * G;
        const double e_lin = linear.Energy(linear.Deform(F));
        const double error = std::abs(element.Energy(element.Deform(F)) / e_lin - 1.0);
        EXPECT_LT(error, 5.0 * eps) << ElasticModelName(model) << " " << d << "D eps " << eps;
        if (previous > 0.0) {
          // First order in eps: halving eps halves the relative error.
          EXPECT_NEAR(previous / error, 2.0, 0.2) << ElasticModelName(model) << " " << d << "D";
        }
        previous = error;
      }
    }
  }
}

// ---- Inversion -------------------------------------------------------------

TEST(Inversion, InvertedElementsAreOutsideTheDomain) {
  for (int d : {2, 3}) {
    for (ElasticModel model : kModels) {
      Element element(Material(model), d);
      Eigen::MatrixXd F = Eigen::MatrixXd::Identity(d, d);
      F(0, 0) = -0.5;  // a reflection: J < 0
      double e = 0.0;
      EXPECT_FALSE(element.Eval(element.Deform(F), &e)) << ElasticModelName(model);
      F(0, 0) = 0.0;  // degenerate: J = 0
      EXPECT_FALSE(element.Eval(element.Deform(F), &e)) << ElasticModelName(model);
    }
  }
}

TEST(Inversion, FirstNonPositiveFindsTheSmallestRoot) {
  // (1 - 2t)(1 - 4t) = 1 - 6t + 8t^2: first root 0.25.
  const double quadratic[3] = {1.0, -6.0, 8.0};
  EXPECT_NEAR(FirstNonPositive(quadratic, 2), 0.25, 1e-15);
  // (1 - t/0.3)(1 - t/0.5)(1 + t): positive until 0.3.
  const double a = 1.0 / 0.3, b = 1.0 / 0.5;
  const double cubic[4] = {1.0, 1.0 - a - b, a * b - a - b, a * b};
  EXPECT_NEAR(FirstNonPositive(cubic, 3), 0.3, 1e-14);
  // A double root touching zero at t = 0.6: 0.36 - 1.2 t + t^2 ... scaled to c0 = 1.
  const double touching[3] = {1.0, -1.2 / 0.36, 1.0 / 0.36};
  EXPECT_NEAR(FirstNonPositive(touching, 2), 0.6, 1e-7);
  // Dips to 0.2 and rises again: no root.
  const double dip[3] = {1.0, -1.6, 1.0};
  EXPECT_EQ(FirstNonPositive(dip, 2), 1.0);
}

// MaxStepSize against dense sampling of det F along random straight paths.
TEST(Inversion, MaxStepSizeIsTheFirstDegenerationOnThePath) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> move(-1.5, 1.5);
  for (int d : {2, 3}) {
    const std::vector<double> rest = RestSimplex(d);
    InversionFilter filter(d, {{0, 1, 2, 3}}, rest);
    int with_root = 0;
    for (int trial = 0; trial < 200; ++trial) {
      std::vector<double> to = rest;
      for (double& c : to) c += move(rng);
      const double t = filter.MaxStepSize(rest.data(), to.data());
      // Sampled: J > 0 up to t, and (if t < 1) J reaches 0 right after.
      const int samples = 2000;
      for (int s = 0; s <= samples; ++s) {
        const double u = t * s / samples;
        std::vector<double> x(rest.size());
        for (size_t i = 0; i < x.size(); ++i) x[i] = rest[i] + u * (to[i] - rest[i]);
        ASSERT_GT(filter.VolumeRatio(x.data(), 0), -1e-12) << "t " << t << " u " << u;
      }
      if (t < 1.0) {
        ++with_root;
        std::vector<double> x(rest.size());
        const double u = std::min(1.0, t + 1e-9);
        for (size_t i = 0; i < x.size(); ++i) x[i] = rest[i] + u * (to[i] - rest[i]);
        EXPECT_LT(filter.VolumeRatio(x.data(), 0), 1e-6);
        EXPECT_FALSE(filter.IsStepValid(to.data()));
      } else {
        EXPECT_TRUE(filter.IsStepValid(to.data()));
      }
    }
    EXPECT_GT(with_root, 20);  // the paths exercise both cases
  }
}

// ---- Scenes ----------------------------------------------------------------

Scene ParseSolidScene(const json& scene) {
  SceneLoadOptions options;
  options.extra_effects = DefaultEffects().UserNames();
  return ParseScene(scene, "solid_test.json", options);
}

std::string LoadError(const json& scene) {
  try {
    ParseSolidScene(scene);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

json SquareScene() {
  return json::parse(R"({
    "effects": ["elasticity"],
    "solid": {"mesh": {"shape": "rectangle", "size": [1, 1], "cells": [2, 2]},
              "model": "neo_hookean", "youngs_modulus": 1e5, "poisson_ratio": 0.4,
              "density": 1000}
  })");
}

TEST(SolidScene, LoadsNodesMassesAndNodeSets) {
  const Scene scene = ParseSolidScene(SquareScene());
  ASSERT_TRUE(scene.solid);
  EXPECT_EQ(scene.num_nodes(), 9);
  EXPECT_EQ(scene.solid->mesh.num_elements(), 8);
  double mass = 0.0;
  for (double m : scene.masses) mass += m;
  EXPECT_NEAR(mass, 1000.0, 1e-9);
  json pinned = SquareScene();
  pinned["pinned"] = {"y_min"};
  EXPECT_EQ(ParseSolidScene(pinned).pinned, (std::vector<int>{0, 1, 2}));
}

TEST(SolidScene, BadInputNamesFileAndKey) {
  const auto with = [](const std::string& pointer, const json& value) {
    json scene = SquareScene();
    scene[json::json_pointer(pointer)] = value;
    return LoadError(scene);
  };
  EXPECT_NE(with("/solid/poisson_ratio", 0.5)
                .find("solid_test.json: solid.poisson_ratio: must be in (-1, 0.5)"),
            std::string::npos);
  EXPECT_NE(with("/solid/youngs_modulus", 0).find("solid.youngs_modulus"), std::string::npos);
  EXPECT_NE(with("/solid/density", -1).find("solid.density"), std::string::npos);
  EXPECT_NE(with("/solid/stiffness", 1).find("solid.stiffness: unknown key"), std::string::npos);
  EXPECT_NE(with("/solid/model", "mooney").find("solid.model: unknown model"), std::string::npos);
  EXPECT_NE(with("/solid/mesh/cells", json::array({0, 2})).find("solid.mesh.cells[0]"),
            std::string::npos);
  EXPECT_NE(with("/solid/mesh/shape", "box").find("solid.mesh.shape"), std::string::npos);
  EXPECT_NE(with("/solid/plane", "membrane").find("solid.plane"), std::string::npos);
  EXPECT_NE(with("/effects", json::array()).find("\"elasticity\" is not listed"),
            std::string::npos);
  EXPECT_NE(with("/solid/mesh", json::object({{"file", "/nonexistent/x.msh"}}))
                .find("solid.mesh.file: cannot open mesh file"),
            std::string::npos);
}

TEST(SolidScene, InvertedOrDegenerateInitialMeshIsRejected) {
  json scene = SquareScene();
  scene["solid"]["mesh"] = json::parse(R"({"nodes": [[0, 0], [1, 0], [0, 1], [1, 1]],
                                           "elements": [[0, 1, 2], [1, 2, 3]]})");
  EXPECT_NE(LoadError(scene).find("solid.mesh: element 1 is inverted"), std::string::npos)
      << LoadError(scene);
  scene["solid"]["mesh"]["elements"] = json::parse("[[0, 1, 2], [1, 3, 2]]");
  EXPECT_EQ(LoadError(scene), "");
  scene["solid"]["mesh"]["nodes"] = json::parse("[[0, 0], [1, 0], [2, 0], [1, 1]]");
  EXPECT_NE(LoadError(scene).find("element 0 is degenerate"), std::string::npos);
}

// A Gmsh file next to the scene file (relative path), its physical groups
// pinned by name.
TEST(SolidScene, GmshFileWithPhysicalGroupsAsNodeSets) {
  const auto dir = std::filesystem::temp_directory_path() / "ipstep_elasticity_test";
  std::filesystem::create_directories(dir);
  GmshShape shape;
  shape.dimension = 3;
  shape.name = "box";
  shape.origin = {-1.0, 0.0, 0.0};
  shape.size = {2.0, 0.5, 0.5};
  shape.element_size = 0.25;
  GmshWriteShape(shape, (dir / "bar.msh").string(), 4.1);
  json scene = {{"dimension", 3},
                {"effects", {"elasticity"}},
                {"solid",
                 {{"mesh", {{"file", "bar.msh"}}},
                  {"youngs_modulus", 1e5},
                  {"poisson_ratio", 0.3},
                  {"density", 100}}},
                {"pinned", {"x_min"}},
                {"moving", {{{"node", "x_max"}, {"velocity", {0.1, 0.0, 0.0}}}}}};
  const auto path = dir / "bar.json";
  std::ofstream(path) << scene.dump();
  SceneLoadOptions options;
  options.extra_effects = DefaultEffects().UserNames();
  const Scene s = LoadSceneFile(path.string(), options);
  ASSERT_TRUE(s.solid);
  EXPECT_GE(s.pinned.size(), 9u);
  for (int i : s.pinned) EXPECT_NEAR(s.positions[3 * i], -1.0, 1e-12);
  EXPECT_GE(s.moving.size(), 9u);
  for (const MovingNode& m : s.moving) EXPECT_NEAR(s.positions[3 * m.node], 1.0, 1e-12);
  // The stretched bar runs without inverting (the inversion filter's check).
  Simulation sim(s, Options("backward_euler", "newton", 0.01, 1e-6));
  for (int step = 0; step < 3; ++step) {
    const StepReport r = sim.Step();
    EXPECT_TRUE(r.converged) << r.status;
  }
}

// Replacing any value of the built-in 2D solid scenes with any other JSON
// value gives a valid scene or one InputError, never another exception.
TEST(SolidScene, MutatedScenesOnlyRaiseInputError) {
  const json replacements =
      json::parse(R"([null, true, "x", -1, 0, 0.5, 2.5, 1e308, [], {}, [0, 1], [1e308, 0]])");
  SceneLoadOptions options;
  options.extra_effects = DefaultEffects().UserNames();
  int errors = 0;
  for (const std::string name : {"squash_square", "cantilever_2d"}) {
    const json original = json::parse(BuiltinSceneText(name));
    const json flat = original.flatten();
    for (const auto& leaf : flat.items()) {
      for (json::json_pointer pointer(leaf.key()); !pointer.empty();
           pointer = pointer.parent_pointer()) {
        for (const json& replacement : replacements) {
          json mutated = original;
          mutated[pointer] = replacement;
          try {
            ParseScene(mutated, "mutated.json", options);
          } catch (const InputError& e) {
            ++errors;
            EXPECT_EQ(std::string(e.what()).rfind("mutated.json: ", 0), 0u) << e.what();
          } catch (const std::exception& e) {
            ADD_FAILURE() << name << " " << pointer.to_string() << " = " << replacement.dump()
                          << ": " << e.what();
          }
        }
      }
    }
  }
  EXPECT_GT(errors, 200);
}

// Tip deflection of a cantilever (length L, height H, clamped at x = 0) under
// its weight, linear model, plane strain, quasi-static: Euler-Bernoulli gives
// w = q L^4 / (8 E' I), q = rho g H, I = H^3 / 12, E' = E / (1 - nu^2).
// Measured relative errors (L/H = 16, nu = 0.3) for 32x2, 64x4, 128x8 cells:
// 0.359, 0.124, 0.0336 (linear triangles are too stiff in bending; the error
// falls by 2.9x and 3.7x, towards 4x per halving: O(h^2)). The limit differs from
// Euler-Bernoulli by the shear deflection (about 1.1 (H/L)^2 = 0.4 %) and the
// clamp's constrained Poisson contraction.
double CantileverTipError(int nx, int ny) {
  const double L = 16.0, H = 1.0, E = 1e7, nu = 0.3, rho = 1.0, g = 9.81;
  json scene = {
      {"effects", {"gravity", "elasticity"}},
      {"gravity", {0.0, -g}},
      {"steps", 1},
      {"time_step", 1.0},
      {"solid",
       {{"mesh",
         {{"shape", "rectangle"}, {"size", {L, H}}, {"cells", {nx, ny}}, {"origin", {0.0, -0.5}}}},
        {"model", "linear"},
        {"youngs_modulus", E},
        {"poisson_ratio", nu},
        {"density", rho}}},
      {"pinned", {"x_min"}}};
  Simulation sim(ParseSolidScene(scene), Options("quasi_static", "newton", 1.0, 1e-4));
  const StepReport report = sim.Step();
  EXPECT_TRUE(report.converged) << report.status;
  // Tip: the node at x = L, y = 0 (the middle of the last column).
  const int tip = (ny / 2) * (nx + 1) + nx;
  const double deflection = -sim.state().x[2 * tip + 1];
  const double I = H * H * H / 12.0, q = rho * g * H, Ep = E / (1.0 - nu * nu);
  const double expected = q * std::pow(L, 4) / (8.0 * Ep * I);
  return std::abs(deflection - expected) / expected;
}

TEST(Cantilever, TipDeflectionConvergesToEulerBernoulli) {
  const double e1 = CantileverTipError(32, 2);
  const double e2 = CantileverTipError(64, 4);
  const double e3 = CantileverTipError(128, 8);
  EXPECT_GT(e1 / e2, 2.5);
  EXPECT_GT(e2 / e3, 2.5);
  EXPECT_LT(e3, 0.04);
}

// First bending frequency of the same cantilever released from rest under
// its weight (it swings about its static deflection, mostly in its first
// mode), Newmark(1/4, 1/2) at about 100 steps per period (period error
// (omega h)^2 / 12 < 1e-3), against Euler-Bernoulli omega_1 =
// 1.8751^2 sqrt(E' I / (rho H L^4)). Measured relative errors for 32x2 and
// 64x4 cells: 0.246, 0.067 (the discretisation is too stiff, as for the
// deflection; the error falls 3.7x per halving).
double CantileverFrequencyError(int nx, int ny) {
  const double L = 16.0, H = 1.0, E = 1e7, nu = 0.3, rho = 1.0, g = 9.81;
  json scene = {
      {"effects", {"gravity", "elasticity"}},
      {"gravity", {0.0, -g}},
      {"solid",
       {{"mesh",
         {{"shape", "rectangle"}, {"size", {L, H}}, {"cells", {nx, ny}}, {"origin", {0.0, -0.5}}}},
        {"model", "linear"},
        {"youngs_modulus", E},
        {"poisson_ratio", nu},
        {"density", rho}}},
      {"pinned", {"x_min"}}};
  const double Ep = E / (1.0 - nu * nu), I = H * H * H / 12.0;
  const double omega = 1.8751 * 1.8751 * std::sqrt(Ep * I / (rho * H * std::pow(L, 4)));
  const double period = 2.0 * M_PI / omega, h = period / 100.0;
  Simulation sim(ParseSolidScene(scene), Options("newmark", "newton", h, 1e-6));
  const int tip = (ny / 2) * (nx + 1) + nx;
  std::vector<double> y = {sim.state().x[2 * tip + 1]};
  for (int step = 0; step < 300; ++step) {
    const StepReport r = sim.Step();
    EXPECT_TRUE(r.converged) << r.status;
    y.push_back(sim.state().x[2 * tip + 1]);
  }
  const double mean =
      0.5 * (*std::max_element(y.begin(), y.end()) + *std::min_element(y.begin(), y.end()));
  // Downward crossings of the mean, linearly interpolated.
  std::vector<double> crossings;
  for (size_t k = 1; k < y.size(); ++k) {
    if (y[k - 1] > mean && y[k] <= mean) {
      crossings.push_back(h * (k - 1 + (y[k - 1] - mean) / (y[k - 1] - y[k])));
    }
  }
  EXPECT_GE(crossings.size(), 2u);
  if (crossings.size() < 2) return 1.0;
  const double measured = (crossings.back() - crossings.front()) / (crossings.size() - 1);
  return std::abs(period / measured - 1.0);  // omega_h / omega - 1
}

TEST(Cantilever, FirstBendingFrequencyConverges) {
  const double e1 = CantileverFrequencyError(32, 2);
  const double e2 = CantileverFrequencyError(64, 4);
  EXPECT_GT(e1 / e2, 3.0);
  EXPECT_LT(e2, 0.08);
}

// A free bar (no gravity, nothing pinned) set vibrating by an initial
// stretching and bending velocity field.
Scene FreeBar(const std::string& model) {
  json scene = {{"effects", {"elasticity"}},
                {"solid",
                 {{"mesh", {{"shape", "rectangle"}, {"size", {4.0, 0.5}}, {"cells", {16, 2}}}},
                  {"model", model},
                  {"youngs_modulus", 1e5},
                  {"poisson_ratio", 0.3},
                  {"density", 100.0}}}};
  Scene s = ParseSolidScene(scene);
  for (int i = 0; i < s.num_nodes(); ++i) {
    const double x = s.positions[2 * i] - 2.0;
    s.velocities[2 * i] = 0.2 * x;
    s.velocities[2 * i + 1] = 0.1 * (x * x - 4.0 / 3.0);
  }
  return s;
}

TEST(ElasticDynamics, NewmarkConservesTheEnergyOfAFreeLinearBar) {
  Simulation sim(FreeBar("linear"), Options("newmark", "newton", 0.01, 1e-11));
  const double initial = sim.Energies().total();
  double max_potential = 0.0;
  for (int step = 0; step < 60; ++step) {
    const StepReport r = sim.Step();
    ASSERT_TRUE(r.converged) << r.status;
    max_potential = std::max(max_potential, r.energies.potential);
    EXPECT_NEAR(r.energies.total(), initial, 1e-8 * initial) << "step " << step;
  }
  EXPECT_GT(max_potential, 0.2 * initial);  // the energy really moves
}

// The same in 3D: a free box bar of linear tetrahedra, twisted and stretched
// by its initial velocity.
TEST(ElasticDynamics, NewmarkConservesTheEnergyOfAFreeLinearBar3D) {
  json scene = {{"dimension", 3},
                {"effects", {"elasticity"}},
                {"solid",
                 {{"mesh", {{"shape", "box"}, {"size", {2.0, 0.4, 0.4}}, {"cells", {8, 2, 2}}}},
                  {"model", "linear"},
                  {"youngs_modulus", 1e5},
                  {"poisson_ratio", 0.3},
                  {"density", 100.0}}}};
  Scene s = ParseSolidScene(scene);
  for (int i = 0; i < s.num_nodes(); ++i) {
    const double x = s.positions[3 * i] - 1.0, y = s.positions[3 * i + 1] - 0.2,
                 z = s.positions[3 * i + 2] - 0.2;
    s.velocities[3 * i] = 0.1 * x;
    s.velocities[3 * i + 1] = -0.3 * x * z;
    s.velocities[3 * i + 2] = 0.3 * x * y;
  }
  Simulation sim(s, Options("newmark", "newton", 0.005, 1e-11));
  const double initial = sim.Energies().total();
  double max_potential = 0.0;
  for (int step = 0; step < 40; ++step) {
    const StepReport r = sim.Step();
    ASSERT_TRUE(r.converged) << r.status;
    max_potential = std::max(max_potential, r.energies.potential);
    EXPECT_NEAR(r.energies.total(), initial, 1e-8 * initial) << "step " << step;
  }
  EXPECT_GT(max_potential, 0.2 * initial);
}

TEST(ElasticDynamics, BackwardEulerDissipatesMonotonically) {
  for (const std::string model : {"linear", "neo_hookean"}) {
    Simulation sim(FreeBar(model), Options("backward_euler", "newton", 0.01, 1e-8));
    const double initial = sim.Energies().total();
    double previous = initial;
    for (int step = 0; step < 60; ++step) {
      const StepReport r = sim.Step();
      ASSERT_TRUE(r.converged) << r.status;
      EXPECT_LE(r.energies.total(), previous * (1.0 + 1e-10)) << model << " step " << step;
      previous = r.energies.total();
    }
    EXPECT_LT(previous, 0.95 * initial) << model;
  }
}

// The square of the course's section 6 (1 m, 4x4 cells, E = 1e5, nu = 0.4,
// rho = 1000) squashed to 40 % of its height between a fixed bottom and a
// top moving down at 1 m/s: no element ever inverts, every step converges.
TEST(ElasticDynamics, SquashNeverInvertsAnElement) {
  for (const std::string optimizer : {"newton", "projected_newton", "lbfgs"}) {
    json scene = SquareScene();
    scene["solid"]["mesh"]["cells"] = {4, 4};
    scene["pinned"] = {"y_min"};
    scene["moving"] = {{{"node", "y_max"}, {"velocity", {0.0, -1.0}}}};
    Simulation sim(ParseSolidScene(scene), Options("backward_euler", optimizer, 0.02, 1e-6));
    const auto names = sim.DiagnosticNames();
    const size_t min_j = std::find(names.begin(), names.end(), "min_J") - names.begin();
    ASSERT_LT(min_j, names.size());
    double smallest = 1.0;
    for (int step = 0; step < 30; ++step) {  // 0.6 m of 1 m
      const StepReport r = sim.Step();
      ASSERT_TRUE(r.converged) << optimizer << " step " << step << ": " << r.status;
      ASSERT_GT(r.diagnostics[min_j], 0.0);
      smallest = std::min(smallest, r.diagnostics[min_j]);
    }
    EXPECT_LT(smallest, 0.5) << optimizer;  // strongly compressed
  }
}

// The seed's foam ball impact as the built-in scene ball_impact_3d (Gmsh
// ball, radius 5 cm, 258 nodes / 898 tetrahedra; E = 1e7, nu = 0.45,
// rho = 1150) at 67 m/s onto a plate, h = 2e-5 s, 200 steps (contact from
// step 8 to about 120): every step converges without substeps, no element
// inverts, no node enters the plate, the ball is squashed (min J < 0.8) and
// bounces back. One test per integrator (about 13 s each on an idle core).
void RunBallImpact(const std::string& integrator) {
  SceneLoadOptions load;
  load.extra_effects = DefaultEffects().UserNames();
  const Scene scene = LoadScene("ball_impact_3d", load);
  ASSERT_EQ(scene.dimension, 3);
  Simulation sim(scene, Options(integrator, "projected_newton", scene.time_step, 1e-5));
  const auto names = sim.DiagnosticNames();
  const size_t min_j = std::find(names.begin(), names.end(), "min_J") - names.begin();
  ASSERT_LT(min_j, names.size());
  double smallest_j = 1.0, lowest = 1.0;
  for (int step = 0; step < scene.steps; ++step) {
    const StepReport r = sim.Step();
    ASSERT_TRUE(r.converged) << integrator << " step " << step << ": " << r.status;
    ASSERT_EQ(r.substeps, 1) << integrator << " step " << step;
    ASSERT_GT(r.diagnostics[min_j], 0.0) << integrator << " step " << step;
    smallest_j = std::min(smallest_j, r.diagnostics[min_j]);
    const Eigen::VectorXd& x = sim.state().x;
    for (int i = 0; i < scene.num_nodes(); ++i) {
      // Every node stays above the plate's top face y = 0 (the ball meets it
      // well inside its 0.3 m x 0.3 m extent).
      ASSERT_LT(std::max(std::abs(x[3 * i]), std::abs(x[3 * i + 2])), 0.15);
      lowest = std::min(lowest, x[3 * i + 1]);
    }
    ASSERT_GT(lowest, 0.0) << integrator << " step " << step;
  }
  double momentum = 0.0, mass = 0.0;
  for (int i = 0; i < scene.num_nodes(); ++i) {
    momentum += scene.masses[i] * sim.state().v[3 * i + 1];
    mass += scene.masses[i];
  }
  EXPECT_LT(smallest_j, 0.8) << integrator;        // strongly squashed
  EXPECT_GT(momentum / mass, 20.0) << integrator;  // rebounding upwards [m/s]
}

TEST(BallImpact, NewmarkNeitherInvertsNorPenetratesNorFails) { RunBallImpact("newmark"); }

TEST(BallImpact, BackwardEulerNeitherInvertsNorPenetratesNorFails) {
  RunBallImpact("backward_euler");
}

// The neo-Hookean element's extended-precision energy (Term::precise_energy,
// element_energy.h) keeps its digits at small strain: at a displacement
// gradient of 1e-8 it matches linear elasticity's mu |eps|^2 + lambda/2
// tr(eps)^2 to the O(strain) nonlinearity (a sum of |F|^2 - 3 and ln J would
// leave a relative error of about 1e-3 there), and at finite strain it is the
// residual form's energy.
TEST(ElasticElement, NeoHookeanPreciseEnergyKeepsSmallStrains) {
  ElasticMaterial material;
  material.model = ElasticModel::kNeoHookean;
  material.youngs_modulus = 1e8;
  material.poisson_ratio = 0.3;
  const double mu = material.mu(), lambda = material.lambda(3);
  const double rest[4][3] = {{0.3, -0.2, 1.1}, {1.3, -0.1, 1.1}, {0.5, 0.8, 1.2}, {0.4, 0.0, 2.1}};
  const double* rest_nodes[4] = {rest[0], rest[1], rest[2], rest[3]};
  const Term term = MakeElasticElementTerm(material, 3, rest_nodes, {0, 1, 2, 3});
  ASSERT_TRUE(static_cast<bool>(term.precise_energy));
  const double g[3][3] = {{0.3, -0.7, 0.2}, {0.5, 0.1, -0.4}, {-0.2, 0.6, 0.9}};
  for (double strain : {1e-8, 1e-3, 0.2}) {
    double x[4][3];
    for (int a = 0; a < 4; ++a) {
      for (int i = 0; i < 3; ++i) {
        x[a][i] = rest[a][i];
        for (int j = 0; j < 3; ++j) x[a][i] += strain * g[i][j] * (rest[a][j] - rest[0][j]);
      }
    }
    const double* p[4] = {x[0], x[1], x[2], x[3]};
    long double energy = 0.0L;
    ASSERT_TRUE(term.precise_energy(p, &energy));
    // The volume: det(Dm) / 6.
    Eigen::Matrix3d dm;
    for (int c = 0; c < 3; ++c) {
      for (int k = 0; k < 3; ++k) dm(k, c) = rest[c + 1][k] - rest[0][k];
    }
    const double volume = dm.determinant() / 6.0;
    Eigen::Matrix3d h =
        strain * Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(&g[0][0]);
    const Eigen::Matrix3d eps = 0.5 * (h + h.transpose());
    const double linear =
        volume * (mu * eps.squaredNorm() + 0.5 * lambda * eps.trace() * eps.trace());
    if (strain < 1e-6) {
      EXPECT_NEAR(static_cast<double>(energy) / linear, 1.0, 1e-6) << strain;
    } else {
      // The residual form: 1/2 rho(|r|^2).
      double r = 0.0;
      ASSERT_TRUE(term.cost->Evaluate(p, &r, nullptr));
      double rho[3];
      term.loss->Evaluate(r * r, rho);
      EXPECT_NEAR(static_cast<double>(energy), 0.5 * rho[0], 1e-9 * 0.5 * rho[0]) << strain;
    }
  }
}

}  // namespace
}  // namespace ipstep
