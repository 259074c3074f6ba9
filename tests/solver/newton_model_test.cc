// The projected Newton model (core/term_hessian.h, solver/newton_model_cost.h):
// per-term Hessians against finite differences of the exact gradient, the
// projection, what Ceres sees through NewtonModelCost, Ceres's first step
// against the Eigen projected Newton direction, quadratic convergence, and
// quasi-static convergence where Gauss-Newton has no lateral stiffness.
#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <vector>

#include <ceres/problem.h>
#include <gtest/gtest.h>
#include <Eigen/Eigenvalues>
#include <Eigen/SparseCholesky>

#include "contact/barrier.h"
#include "contact/contact_terms.h"
#include "contact/friction.h"
#include "contact/obstacles/sphere_obstacle.h"
#include "core/term_hessian.h"
#include "energies/elasticity/elasticity_effect.h"
#include "energies/hookean_spring.h"
#include "energies/quartic_spring.h"
#include "energies/rayleigh_mass_damping.h"
#include "energies/squared_strain_spring.h"
#include "energies/term_builder.h"
#include "sim/simulation.h"
#include "solver/newton_model_cost.h"
#include "solver/projected_newton_solver.h"
#include "solver/trust_region_solver.h"
#include "tests/support/test_scenes.h"

namespace ipstep {
namespace {

using testing::ClothScene;
using testing::Options;

// A functor without analytic curvature or declarations: Newton models take
// central differences of its autodiff Jacobian. e = 1/2 |r|^2 with two
// residuals that are nonlinear in all three nodes (an angle-like energy).
template <int kDim>
struct BendingLike {
  template <typename T>
  bool operator()(const T* a, const T* b, const T* c, T* residual) const {
    T cross = (b[0] - a[0]) * (c[1] - b[1]) - (b[1] - a[1]) * (c[0] - b[0]);
    T dot = T(0.0);
    for (int k = 0; k < kDim; ++k) dot += (b[k] - a[k]) * (c[k] - b[k]);
    residual[0] = 3.0 * cross;
    residual[1] = 0.5 * dot * dot - 0.1;
    return true;
  }
};

// More residuals than a term has parameters: 30 on two nodes.
template <int kDim>
struct ManyResiduals {
  template <typename T>
  bool operator()(const T* a, const T* b, T* residual) const {
    for (int k = 0; k < 30; ++k) {
      const double angle = 0.37 * k;
      T along = T(0.0);
      for (int d = 0; d < kDim; ++d)
        along += (d % 2 == 0 ? cos(angle) : sin(angle)) * (b[d] - a[d]);
      residual[k] = along * along - 0.01 * k;
    }
    return true;
  }
};

// Terms built through a TermBuilder on a throwaway scene of `nodes` nodes.
struct TermFactory {
  TermFactory(int dimension, int nodes) : potential(dimension, nodes) {
    scene.dimension = dimension;
    state.dimension = dimension;
    state.x = Eigen::VectorXd::Zero(dimension * nodes);
    state.mass = Eigen::VectorXd::Ones(nodes);
    state.kind.assign(nodes, NodeKind::kFree);
    potential.context().velocity_slope = 7.0;  // v(x) = 7 x for the damping term
  }
  TermBuilder builder() { return TermBuilder(scene, state, true, &potential); }
  const Term& last() const { return potential.terms().back(); }
  Scene scene;
  State state;
  IncrementalPotential potential;
};

// Parameter blocks of a term at x (per node, `dimension` values each).
std::vector<const double*> Blocks(const std::vector<std::vector<double>>& x) {
  std::vector<const double*> blocks;
  for (const auto& b : x) blocks.push_back(b.data());
  return blocks;
}

// Central differences of the model gradient over the model coordinates (for
// pair-difference terms, d moves with x_1).
TermMatrix GradientDifferences(const Term& term, int dim, double weight,
                               std::vector<std::vector<double>> x, double step) {
  TermModelEvaluator evaluator;
  TermModel plus, minus;
  const int n = ModelSize(term, dim);
  TermMatrix h(n, n);
  for (int j = 0; j < n; ++j) {
    double& coordinate = term.pair_difference ? x[1][j] : x[j / dim][j % dim];
    const double saved = coordinate;
    coordinate = saved + step;
    EXPECT_TRUE(evaluator.Evaluate(term, dim, weight, Blocks(x).data(), true, &plus));
    coordinate = saved - step;
    EXPECT_TRUE(evaluator.Evaluate(term, dim, weight, Blocks(x).data(), true, &minus));
    coordinate = saved;
    h.col(j) = (plus.gradient - minus.gradient) / (2.0 * step);
  }
  return h;
}

void ExpectModelHessianIsExact(const Term& term, int dim, const std::vector<std::vector<double>>& x,
                               double relative_tolerance, const char* what) {
  const double weight = 2.5;
  TermModelEvaluator evaluator;
  TermModel model;
  ASSERT_TRUE(evaluator.Evaluate(term, dim, weight, Blocks(x).data(), true, &model)) << what;
  const TermMatrix reference = GradientDifferences(term, dim, weight, x, 1e-6);
  // Relative to the Hessian, or to its Gauss-Newton part where the two
  // second-order parts cancel (sliding friction's exact Hessian is zero).
  const double scale = std::max(reference.cwiseAbs().maxCoeff(), model.gauss_newton_scale);
  ASSERT_GT(scale, 0.0) << what;
  EXPECT_LE((model.hessian - reference).cwiseAbs().maxCoeff(), relative_tolerance * scale)
      << what << "\nmodel\n"
      << model.hessian << "\nfinite differences\n"
      << reference;
  EXPECT_FALSE(model.curvature_dropped) << what;
}

TEST(TermHessian, SpringsMatchFiniteDifferencesOfTheGradientIn2DAnd3D) {
  const std::vector<std::vector<double>> compressed = {{0.1, -0.2, 0.3}, {0.5, 0.1, -0.1}};
  const std::vector<std::vector<double>> stretched = {{0.1, -0.2, 0.3}, {1.9, 0.8, -0.6}};
  for (int dim : {2, 3}) {
    for (const auto& x : {compressed, stretched}) {
      std::vector<std::vector<double>> blocks = x;
      for (auto& b : blocks) b.resize(dim);
      TermFactory factory(dim, 2);
      TermBuilder builder = factory.builder();
      builder.AddAutoDiff<HookeanSpring, 1, 2>(TermKind::kPotential, {0, 1}, 40.0, 1.0);
      ExpectModelHessianIsExact(factory.last(), dim, blocks, 1e-7, "hookean");
      EXPECT_TRUE(factory.last().pair_difference);
      EXPECT_TRUE(static_cast<bool>(factory.last().curvature));
      builder.AddAutoDiff<SquaredStrainSpring, 1, 2>(TermKind::kPotential, {0, 1}, 40.0, 1.0);
      ExpectModelHessianIsExact(factory.last(), dim, blocks, 1e-7, "squared_strain");
      builder.AddAutoDiff<QuarticSpring, 1, 2>(TermKind::kPotential, {0, 1}, 40.0, 1.0);
      ExpectModelHessianIsExact(factory.last(), dim, blocks, 1e-7, "quartic");
    }
  }
}

TEST(TermHessian, AnalyticSpringCurvatureEqualsFiniteDifferencesOfTheJacobian) {
  // The same spring with its analytic curvature removed: the model falls back
  // to central differences of the autodiff Jacobian (O(1e-8) relative).
  const std::vector<std::vector<double>> x = {{0.1, -0.2, 0.3}, {0.5, 0.1, -0.1}};
  TermFactory factory(3, 2);
  TermBuilder builder = factory.builder();
  builder.AddAutoDiff<HookeanSpring, 1, 2>(TermKind::kPotential, {0, 1}, 40.0, 1.0);
  builder.AddAutoDiff<HookeanSpring, 1, 2>(TermKind::kPotential, {0, 1}, 40.0, 1.0);
  Term& numeric = const_cast<Term&>(factory.potential.terms()[1]);
  numeric.curvature = nullptr;
  TermModelEvaluator evaluator;
  TermModel analytic_model, numeric_model;
  ASSERT_TRUE(evaluator.Evaluate(factory.potential.terms()[0], 3, 1.0, Blocks(x).data(), true,
                                 &analytic_model));
  ASSERT_TRUE(evaluator.Evaluate(numeric, 3, 1.0, Blocks(x).data(), true, &numeric_model));
  const double scale = analytic_model.hessian.cwiseAbs().maxCoeff();
  EXPECT_LE((analytic_model.hessian - numeric_model.hessian).cwiseAbs().maxCoeff(), 1e-7 * scale);
  // A compressed Hookean spring: the exact Hessian has a negative eigenvalue
  // across the spring (k (1 - L/|d|) < 0), which Gauss-Newton lacks.
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(
      analytic_model.hessian.topLeftCorner<3, 3>());
  EXPECT_LT(eigen.eigenvalues()[0], -1.0);
}

TEST(TermHessian, FiniteDifferenceModelOfAUserFunctorIsExactToFiniteDifferences) {
  const std::vector<std::vector<double>> x = {{0.1, -0.2}, {0.7, 0.3}, {1.1, -0.4}};
  TermFactory factory(2, 3);
  TermBuilder builder = factory.builder();
  builder.AddAutoDiff<BendingLike, 2, 3>(TermKind::kPotential, {0, 1, 2});
  EXPECT_FALSE(factory.last().pair_difference);
  EXPECT_FALSE(static_cast<bool>(factory.last().curvature));
  ExpectModelHessianIsExact(factory.last(), 2, x, 1e-6, "user functor (finite differences)");
}

TEST(TermHessian, TermsWithMoreResidualsThanParameters) {
  const std::vector<std::vector<double>> x = {{0.1, -0.2, 0.3}, {0.7, 0.3, -0.5}};
  for (int dim : {2, 3}) {
    TermFactory factory(dim, 2);
    TermBuilder builder = factory.builder();
    builder.AddAutoDiff<ManyResiduals, 30, 2>(TermKind::kPotential, {0, 1});
    std::vector<std::vector<double>> blocks = x;
    for (auto& b : blocks) b.resize(dim);
    ExpectModelHessianIsExact(factory.last(), dim, blocks, 1e-6, "30 residuals");
  }
}

TEST(TermHessian, AffineTermsKeepTheirExactGaussNewtonModel) {
  const std::vector<std::vector<double>> x = {{0.3, -0.7}};
  TermFactory factory(2, 1);
  TermBuilder builder = factory.builder();
  builder.AddAutoDiff<RayleighMassDamping, kOneResidualPerCoordinate, 1>(
      TermKind::kDissipation, {0}, builder.context(), 0, 3.0);
  EXPECT_TRUE(factory.last().gauss_newton_model);
  ExpectModelHessianIsExact(factory.last(), 2, x, 1e-8, "mass damping");
}

// Contact terms, losses included: a barrier against a sphere (analytic
// curvature through BarrierLoss), friction against an obstacle in 2D (the
// one-sided halves with their loss) and 3D, and 2D edge friction (finite
// differences of their Jacobians).
TEST(TermHessian, ContactTermsMatchFiniteDifferencesOfTheGradient) {
  const SphereObstacle sphere(3, Eigen::Vector3d::Zero(), 0.5);
  const double time = 0.0, kappa = 3e3;
  {
    Term term;
    term.nodes = {0};
    auto cost = std::make_unique<PointObstacleGap>(3, &sphere, &time, 0.1, 0.0);
    term.curvature = GapCurvature(cost.get());
    term.cost = std::move(cost);
    term.loss = std::make_unique<BarrierLoss>(0.1, 0.2, &kappa);
    ExpectModelHessianIsExact(term, 3, {{0.3, 0.4, 0.2}}, 1e-6, "barrier, sphere");
  }
  // Friction: positions x at the velocity map's base, so v = v_base there;
  // tangential speeds below eps_v (sticking) and above (sliding) on the side
  // each one-sided half acts.
  const double eps_v = 1e-2, c = kFrictionSpeedScale * eps_v;
  const std::vector<std::vector<double>> x2 = {{0.1, 0.2}, {0.3, 0.41}, {0.52, 0.6}};
  StepContext context;
  context.Resize(2, 3);
  context.velocity_slope = 50.0;
  for (int b = 0; b < 3; ++b) context.x_base.segment<2>(2 * b) << x2[b][0], x2[b][1];
  Eigen::Matrix3d tangents = Eigen::Matrix3d::Zero();
  tangents.col(0) = Eigen::Vector3d(0.6, 0.8, 0);
  for (int side : {1, -1}) {
    for (double speed : {0.004, 0.05}) {
      // Node 1 moves at side * speed along the tangent; nodes 0 and 2 rest.
      context.v_base.setZero();
      context.v_base.segment<2>(2) = side * speed * Eigen::Vector2d(0.6, 0.8);
      Term term;
      term.kind = TermKind::kDissipation;
      term.nodes = {1};
      term.cost = std::make_unique<ObstacleFriction>(&context, 1, tangents, Eigen::Vector3d::Zero(),
                                                     eps_v, side, c);
      term.loss = std::make_unique<OneSidedFrictionLoss>(4.0, c, eps_v);
      ExpectModelHessianIsExact(term, 2, {x2[1]}, 1e-5, "2D obstacle friction");
      Term edge;
      edge.kind = TermKind::kDissipation;
      edge.nodes = {1, 0, 2};
      edge.cost = std::make_unique<EdgeFriction>(&context, 1, 0, 2, Eigen::Vector2d(0.6, 0.8), 0.3,
                                                 side, c);
      edge.loss = std::make_unique<OneSidedFrictionLoss>(4.0, c, eps_v);
      ExpectModelHessianIsExact(edge, 2, {x2[1], x2[0], x2[2]}, 1e-5, "2D edge friction");
    }
  }
  StepContext context3;
  context3.Resize(3, 1);
  context3.velocity_slope = 20.0;
  Eigen::Matrix3d tangents3 = Eigen::Matrix3d::Zero();
  tangents3.col(0) = Eigen::Vector3d(1, 0, 0);
  tangents3.col(1) = Eigen::Vector3d(0, 0, 1);
  for (double speed : {0.004, 0.05}) {  // sticking, sliding
    context3.v_base << 0.6 * speed, 0.3, 0.8 * speed;
    Term term;
    term.kind = TermKind::kDissipation;
    term.nodes = {0};
    term.cost =
        std::make_unique<ObstacleFriction>(&context3, 0, tangents3, Eigen::Vector3d::Zero(), eps_v);
    term.loss = std::make_unique<FrictionLoss>(4.0);
    ExpectModelHessianIsExact(term, 3, {{0.0, 0.0, 0.0}}, 1e-5, "3D obstacle friction");
  }
}

TEST(TermHessian, ProjectionFloorsNegativeCurvatureAndKeepsPositiveDefiniteModels) {
  TermModel model;
  model.hessian = TermMatrix::Zero(3, 3);
  model.hessian.diagonal() << 4.0, -2.0, 1.0;
  model.gauss_newton_scale = 0.0;
  ProjectedHessian projected;
  ProjectHessian(model, &projected);
  const TermMatrix h =
      projected.vectors * projected.values.asDiagonal() * projected.vectors.transpose();
  Eigen::Vector3d expected(4.0, kCurvatureFloor * 4.0, 1.0);
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(h(i, i), expected[i], 1e-14);
  EXPECT_NEAR(h(0, 1), 0.0, 1e-14);
  // A positive definite Hessian is returned as it is.
  model.hessian << 4.0, 1.0, 0.0, 1.0, 3.0, 0.5, 0.0, 0.5, 2.0;
  ProjectHessian(model, &projected);
  const TermMatrix same =
      projected.vectors * projected.values.asDiagonal() * projected.vectors.transpose();
  EXPECT_LE((same - model.hessian).cwiseAbs().maxCoeff(), 1e-14);
}

// What Ceres sees of one NewtonModelCost block at x: its cost, gradient and
// dense Jacobian, through Problem::Evaluate.
struct CeresView {
  bool ok = false;
  double cost = 0.0;
  std::vector<double> gradient;
  Eigen::MatrixXd jacobian;
};

CeresView EvaluateInCeres(NewtonModelCost* cost, std::vector<std::vector<double>>* x) {
  NewtonModelLoss loss(cost);
  ceres::Problem::Options options;
  options.cost_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  options.loss_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  ceres::Problem problem(options);
  std::vector<double*> blocks;
  for (auto& b : *x) blocks.push_back(b.data());
  problem.AddResidualBlock(cost, &loss, blocks);
  CeresView view;
  ceres::CRSMatrix jacobian;
  view.ok = problem.Evaluate(ceres::Problem::EvaluateOptions(), &view.cost, nullptr, &view.gradient,
                             &jacobian);
  view.jacobian = Eigen::MatrixXd::Zero(jacobian.num_rows, jacobian.num_cols);
  for (int r = 0; r < jacobian.num_rows; ++r) {
    for (int k = jacobian.rows[r]; k < jacobian.rows[r + 1]; ++k) {
      view.jacobian(r, jacobian.cols[k]) = jacobian.values[k];
    }
  }
  return view;
}

// What Ceres sees: a problem with the one residual block NewtonModelCost +
// NewtonModelLoss has cost e, gradient g and J^T J = the projected Hessian.
TEST(NewtonModelCost, CeresSeesTheEnergyTheGradientAndTheProjectedHessian) {
  for (int dim : {2, 3}) {
    TermFactory factory(dim, 3);
    TermBuilder builder = factory.builder();
    builder.AddAutoDiff<HookeanSpring, 1, 2>(TermKind::kPotential, {0, 1}, 40.0, 1.0);
    builder.AddAutoDiff<BendingLike, 2, 3>(TermKind::kPotential, {0, 1, 2});
    for (const Term& term : factory.potential.terms()) {
      std::vector<std::vector<double>> x = {{0.1, -0.2, 0.3}, {0.5, 0.1, -0.1}, {1.1, -0.4, 0.2}};
      x.resize(term.nodes.size());
      for (auto& b : x) b.resize(dim);
      const double weight = 2.5;
      const bool veto = false;
      NewtonModelCost cost(&term, dim, &weight, &veto);
      const CeresView view = EvaluateInCeres(&cost, &x);
      ASSERT_TRUE(view.ok);
      const double ceres_cost = view.cost;
      const std::vector<double>& gradient = view.gradient;
      TermModelEvaluator evaluator;
      TermModel model;
      ASSERT_TRUE(evaluator.Evaluate(term, dim, weight, Blocks(x).data(), true, &model));
      ProjectedHessian projected;
      ProjectHessian(model, &projected);
      TermMatrix h =
          projected.vectors * projected.values.asDiagonal() * projected.vectors.transpose();
      EXPECT_NEAR(ceres_cost, model.energy, 1e-14 * std::abs(model.energy));
      // Full coordinates: pair-difference models expand to [[K, -K], [-K, K]].
      const int nt = dim * static_cast<int>(term.nodes.size());
      Eigen::MatrixXd full_h(nt, nt);
      Eigen::VectorXd full_g(nt);
      for (int a = 0; a < nt; ++a) {
        const int n = static_cast<int>(h.rows());
        full_g[a] =
            term.pair_difference ? (a < n ? -1.0 : 1.0) * model.gradient[a % n] : model.gradient[a];
        for (int b = 0; b < nt; ++b) {
          full_h(a, b) =
              term.pair_difference ? ((a < n) == (b < n) ? 1.0 : -1.0) * h(a % n, b % n) : h(a, b);
        }
      }
      const Eigen::MatrixXd& j = view.jacobian;
      const double scale = full_h.cwiseAbs().maxCoeff();
      EXPECT_LE((j.transpose() * j - full_h).cwiseAbs().maxCoeff(), 1e-12 * scale);
      for (int a = 0; a < nt; ++a) {
        EXPECT_NEAR(gradient[a], full_g[a], 1e-12 * full_g.cwiseAbs().maxCoeff());
      }
    }
  }
}

// An elastic element's Newton model in Ceres (a reduced model, one row per
// F-space coordinate): the gradient exact; where every F-space eigenvalue is
// positive (stretched) J^T J is the exact Hessian; under compression (negative
// twist eigenvalues) J^T J - H is positive semi-definite, clamp adds what the
// negative modes lack and the absolute filter twice that (up to the floor).
TEST(NewtonModelCost, ElasticElementsProjectInFSpace) {
  for (ElasticModel model :
       {ElasticModel::kNeoHookean, ElasticModel::kStvk, ElasticModel::kFixedCorotated}) {
    for (int dim : {2, 3}) {
      ElasticMaterial material;
      material.model = model;
      material.youngs_modulus = 1e5;
      material.poisson_ratio = 0.3;
      const double rest[4][3] = {{0, 0, 0}, {1, 0.1, 0}, {0.2, 1, 0.1}, {0.1, 0.2, 1}};
      const double* rest_nodes[4] = {rest[0], rest[1], rest[2], rest[3]};
      const Term term = MakeElasticElementTerm(material, dim, rest_nodes, {0, 1, 2, 3});
      ASSERT_TRUE(static_cast<bool>(term.reduced_model));
      // The same element through the residual path: its exact Hessian.
      Term generic = MakeElasticElementTerm(material, dim, rest_nodes, {0, 1, 2, 3});
      generic.reduced_model = nullptr;
      for (double scale : {1.05, 0.8}) {  // stretched, compressed
        SCOPED_TRACE(std::string(ElasticModelName(model)) + " " + std::to_string(dim) + "D x" +
                     std::to_string(scale));
        std::vector<std::vector<double>> x(dim + 1, std::vector<double>(dim));
        for (int a = 0; a <= dim; ++a) {
          for (int k = 0; k < dim; ++k) {
            x[a][k] = scale * rest[a][k] + (k == 0 ? 0.1 * rest[a][1] : 0.0);  // + a shear
          }
        }
        TermModelEvaluator evaluator;
        TermModel exact;
        ASSERT_TRUE(evaluator.Evaluate(generic, dim, 1.0, Blocks(x).data(), true, &exact));
        const int n = dim * (dim + 1);
        Eigen::MatrixXd projection[2];
        for (int f = 0; f < 2; ++f) {
          const EigenvalueFilter filter =
              f == 0 ? EigenvalueFilter::kClamp : EigenvalueFilter::kAbsolute;
          const double weight = 1.0;
          const bool veto = false;
          NewtonModelCost cost(&term, dim, &weight, &veto, &filter);
          EXPECT_EQ(cost.num_residuals(), dim * dim);
          const CeresView view = EvaluateInCeres(&cost, &x);
          ASSERT_TRUE(view.ok);
          const double ceres_cost = view.cost;
          const std::vector<double>& gradient = view.gradient;
          EXPECT_NEAR(ceres_cost, exact.energy, 1e-12 * std::abs(exact.energy));
          for (int a = 0; a < n; ++a) {
            EXPECT_NEAR(gradient[a], exact.gradient[a],
                        1e-9 * exact.gradient.cwiseAbs().maxCoeff());
          }
          const Eigen::MatrixXd& j = view.jacobian;
          projection[f] = j.transpose() * j;
        }
        const Eigen::MatrixXd h = exact.hessian;
        const double s = h.cwiseAbs().maxCoeff();
        const Eigen::MatrixXd added = projection[0] - h;
        const double smallest =
            Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(added).eigenvalues().minCoeff();
        EXPECT_GE(smallest, -1e-9 * s);
        if (scale > 1.0) {
          EXPECT_LE(added.cwiseAbs().maxCoeff(), 1e-7 * s);  // nothing to clamp
        } else {
          EXPECT_GT(added.cwiseAbs().maxCoeff(), 1e-4 * s);  // something was clamped
        }
        EXPECT_LE((projection[1] - h - 2.0 * added).cwiseAbs().maxCoeff(), 1e-6 * s);
      }
    }
  }
}

// The first Ceres newton iteration is the projected Newton step: the same
// model, Levenberg-Marquardt with radius 1e16 adds a damping of 1e-16.
TEST(NewtonModel, CeresFirstStepEqualsTheEigenProjectedNewtonDirection) {
  for (const char* integrator : {"backward_euler", "quasi_static"}) {
    SimulationOptions options = Options(integrator, "newton", 1.0 / 60.0, 1e-12);
    options.optimizer.max_iterations = 1;
    options.optimizer.backtrack_rejected_steps = false;
    Simulation sim(ClothScene(10, 2e3), options);
    IncrementalPotential* potential = nullptr;
    sim.ReplaceStepSolver([&](IncrementalPotential* p, const State* s) {
      potential = p;
      return MakeStepSolver(p, s, options.optimizer);
    });
    Eigen::VectorXd start;
    sim.variational_integrator()->Predict(sim.state(), sim.gravity(), sim.time_step(),
                                          &potential->context(), &start);
    sim.state().PrescribedPositions(sim.time_step(), &start);
    // Perturb the guess so that springs are both stretched and compressed.
    for (int d = 0; d < start.size(); ++d) start[d] += 0.004 * std::sin(7.0 * d);
    sim.state().PrescribedPositions(sim.time_step(), &start);
    OptimizerOptions reference_options = options.optimizer;
    reference_options.optimizer = Optimizer::kProjectedNewton;
    ProjectedNewtonSolver reference(potential, &sim.state(), reference_options);
    ASSERT_TRUE(reference.AssembleHessian(start));
    // The direction from the assembled model.
    Eigen::VectorXd gradient(start.size());
    double energy = 0.0;
    ASSERT_TRUE(potential->Evaluate(start.data(), &energy, gradient.data()));
    const auto& free = reference.free_index();
    Eigen::VectorXd free_gradient(reference.hessian().rows());
    for (size_t d = 0; d < free.size(); ++d) {
      if (free[d] >= 0) free_gradient[free[d]] = gradient[d];
    }
    Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>, Eigen::Lower> ldlt(reference.hessian());
    ASSERT_EQ(ldlt.info(), Eigen::Success);
    const Eigen::VectorXd free_step = ldlt.solve(-free_gradient);
    TrustRegionSolver ceres_solver(potential, &sim.state(), options.optimizer);
    Eigen::VectorXd x = start;
    const StepSolveResult result = ceres_solver.Solve(&x);
    ASSERT_EQ(result.iterations, 1) << result.status;
    double difference = 0.0;
    for (size_t d = 0; d < free.size(); ++d) {
      if (free[d] < 0) continue;
      difference = std::max(difference, std::abs((x[d] - start[d]) - free_step[free[d]]));
    }
    EXPECT_LE(difference, 1e-9 * free_step.lpNorm<Eigen::Infinity>()) << integrator;
    EXPECT_GT(free_step.lpNorm<Eigen::Infinity>(), 1e-4) << integrator;
  }
}

// n nodes of `mass` on the x axis, `spacing` apart and at rest, joined by
// Hookean springs k = 100 of rest length `rest_length`; no pins, no effects.
Scene HorizontalChain(const char* name, int n, double spacing, double rest_length, double mass) {
  Scene scene;
  scene.name = scene.source = name;
  for (int i = 0; i < n; ++i) {
    scene.positions.push_back(spacing * i);
    scene.positions.push_back(0.0);
    scene.masses.push_back(mass);
  }
  scene.velocities.assign(2 * n, 0.0);
  for (int i = 0; i + 1 < n; ++i) {
    scene.springs.push_back(Spring{i, i + 1, SpringModel::kHookean, 100.0, rest_length});
  }
  return scene;
}

// Residual sequence of one step.
std::vector<double> Residuals(const Scene& scene, const SimulationOptions& options,
                              StepReport* report) {
  Simulation sim(scene, options);
  std::vector<double> residuals;
  sim.set_iteration_sink([&](const IterationRecord& r) { residuals.push_back(r.residual); });
  *report = sim.Step();
  return residuals;
}

// A stretched chain (every spring in tension: the Hessian is positive
// definite, nothing is projected) pulled sideways: Newton converges
// quadratically, Gauss-Newton linearly.
TEST(NewtonModel, QuadraticConvergenceOnASmoothConvexStep) {
  const int n = 8;
  Scene scene = HorizontalChain("stretched_chain", n, 1.2, 1.0, 0.01);
  for (int i = 1; i + 1 < n; ++i) scene.velocities[2 * i + 1] = 30.0 * std::sin(0.9 * i);
  scene.pinned = {0, n - 1};
  scene.effects = {"springs"};
  StepReport report;
  const std::vector<double> newton =
      Residuals(scene, Options("backward_euler", "newton", 0.05, 1e-7), &report);
  ASSERT_TRUE(report.converged) << report.status;
  ASSERT_GE(newton.size(), 4u);
  int quadratic_pairs = 0;
  for (size_t k = 0; k + 1 < newton.size(); ++k) {
    const double r = newton[k] / newton[0], next = newton[k + 1] / newton[0];
    // Above round-off (relative 1e-9: the sequence stagnates near 2e-11).
    if (r < 1e-2 && next > 1e-9) {
      EXPECT_LE(next, 10.0 * r * r) << "iteration " << k;
      ++quadratic_pairs;
    }
  }
  EXPECT_GE(quadratic_pairs, 1);
  // Gauss-Newton (no geometric stiffness) does not get there in 100 iterations.
  Residuals(scene, Options("backward_euler", "gauss_newton", 0.05, 1e-7), &report);
  EXPECT_FALSE(report.converged);
  EXPECT_EQ(report.iterations, 100);
}

// Quasi-static: a chain released horizontally finds its hanging equilibrium.
// Its lateral stiffness is purely geometric (tension / length), which
// Gauss-Newton drops; the Newton model has it.
TEST(NewtonModel, QuasiStaticNewtonConvergesOnAChainAndOnTheCloth) {
  const int n = 21;
  Scene chain = HorizontalChain("horizontal_chain", n, 0.05, 0.05, 0.1 / n);
  chain.pinned = {0};
  chain.gravity = {0.0, -9.81};
  chain.effects = {"gravity", "springs"};
  chain.time_step = 0.01;
  for (const Scene& scene : {chain, ClothScene(20)}) {
    for (const char* optimizer : {"newton", "projected_newton"}) {
      Simulation sim(scene, Options("quasi_static", optimizer, 0.01, 1e-6));
      for (int step = 0; step < 5; ++step) {
        const StepReport r = sim.Step();
        EXPECT_TRUE(r.converged) << scene.name << " " << optimizer << " step " << step << ": "
                                 << r.status;
      }
      // Hanging: the free end below the pin.
      const int last = scene.num_nodes() - 1;
      EXPECT_LT(sim.state().x[2 * last + 1], -0.5) << scene.name;
    }
  }
  // Gauss-Newton, for contrast, does not converge on the chain's first step.
  Simulation sim(chain, Options("quasi_static", "gauss_newton", 0.01, 1e-6));
  EXPECT_FALSE(sim.Step().converged);
}

}  // namespace
}  // namespace ipstep
