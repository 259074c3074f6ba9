// --num_threads changes who computes, not what: the terms' energies,
// gradients and Newton models are computed on the potential's thread pool
// (core/thread_pool.h) and summed in term order, so every optimiser takes
// the same iterates, bit for bit, for any number of threads. Each scene has
// more terms than one thread keeps to itself (IncrementalPotential::kEnergyGrain and kModelGrain).
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/thread_pool.h"
#include "problems/scene_loader.h"
#include "sim/default_effects.h"
#include "sim/simulation.h"
#include "tests/support/test_scenes.h"

namespace ipstep {
namespace {

struct Trajectory {
  std::vector<int> iterations;
  std::vector<double> residuals;
  Eigen::VectorXd x;
};

Trajectory RunWith(const Scene& scene, const std::string& integrator, const std::string& optimizer,
                   int threads, int steps,
                   HessianProjection projection = HessianProjection::kAlways) {
  SimulationOptions options = testing::Options(integrator, optimizer, scene.time_step, 1e-7);
  options.optimizer.num_threads = threads;
  options.optimizer.hessian_projection = projection;
  options.steps = steps;
  Simulation sim(scene, options);
  Trajectory run;
  for (int s = 0; s < steps; ++s) {
    const StepReport report = sim.Step();
    run.iterations.push_back(report.iterations);
    run.residuals.push_back(report.residual);
  }
  run.x = sim.state().x;
  return run;
}

Scene Builtin(const std::string& name) {
  SceneLoadOptions load;
  load.extra_effects = DefaultEffects().UserNames();
  return LoadScene(name, load);
}

TEST(ThreadCount, SameIteratesForAnyNumberOfThreads) {
  const Scene bar = Builtin("twisted_bar_3d");  // 480 tetrahedra, 189 nodes
  const Scene cloth = testing::ClothScene(24);  // 576 nodes, about 2,200 springs
  const struct {
    const Scene* scene;
    const char* integrator;
    const char* optimizer;
    HessianProjection projection;
    int steps;
  } cases[] = {
      {&bar, "backward_euler", "projected_newton", HessianProjection::kAlways, 4},
      {&bar, "backward_euler", "projected_newton", HessianProjection::kProgressive, 4},
      {&bar, "newmark", "newton", HessianProjection::kTrustRegion, 4},
      {&bar, "backward_euler", "lbfgs", HessianProjection::kAlways, 2},
      {&cloth, "backward_euler", "newton", HessianProjection::kAlways, 4},
      {&cloth, "backward_euler", "projected_newton", HessianProjection::kWhenIndefinite, 4},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(std::string(c.scene->name) + " " + c.integrator + " " + c.optimizer + " " +
                 HessianProjectionName(c.projection));
    const Trajectory one = RunWith(*c.scene, c.integrator, c.optimizer, 1, c.steps, c.projection);
    for (int threads : {2, 3}) {
      const Trajectory many =
          RunWith(*c.scene, c.integrator, c.optimizer, threads, c.steps, c.projection);
      EXPECT_EQ(many.iterations, one.iterations) << threads << " threads";
      EXPECT_EQ(many.residuals, one.residuals) << threads << " threads";
      EXPECT_EQ(many.x, one.x) << threads << " threads";
    }
  }
}

// The pool itself: every index once, on a thread of the team, for loops of
// any length, one after another.
TEST(ThreadCount, ParallelForVisitsEveryIndexOnce) {
  ThreadPool pool(3);
  EXPECT_EQ(pool.num_threads(), 3);
  for (int n : {0, 1, 5, 100, 10007}) {
    std::vector<int> visits(n, 0);
    std::vector<int> thread_of(n, -1);
    pool.ParallelFor(n, 1, [&](int begin, int end, int thread) {
      for (int i = begin; i < end; ++i) {
        ++visits[i];
        thread_of[i] = thread;
      }
    });
    for (int i = 0; i < n; ++i) {
      ASSERT_EQ(visits[i], 1) << "n " << n << " index " << i;
      ASSERT_GE(thread_of[i], 0);
      ASSERT_LT(thread_of[i], 3);
    }
  }
}

}  // namespace
}  // namespace ipstep
