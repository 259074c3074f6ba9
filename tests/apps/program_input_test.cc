// The ipstep program on bad input: one clear error naming the file or flag and
// key, exit code 2, never a crash or an abort. And the good path: outputs.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "tests/support/run_program.h"

namespace {

namespace fs = std::filesystem;

using Outcome = ipstep::testing::ProgramOutcome;

Outcome RunIpstep(const std::string& arguments) {
  return ipstep::testing::RunProgram(IPSTEP_BINARY, arguments);
}

class ProgramInput : public ipstep::testing::ProgramTest {
 protected:
  void ExpectInputError(const std::string& arguments, const std::string& where,
                        const std::string& key) {
    const Outcome o = RunIpstep(arguments);
    EXPECT_EQ(o.exit_code, 2) << arguments << "\n" << o.output;
    EXPECT_NE(o.output.find(where), std::string::npos) << arguments << "\n" << o.output;
    EXPECT_NE(o.output.find(key), std::string::npos) << arguments << "\n" << o.output;
    EXPECT_EQ(o.output.find("Check failed"), std::string::npos) << o.output;
    // One error line.
    EXPECT_EQ(std::count(o.output.begin(), o.output.end(), '\n'), 1) << o.output;
  }
};

const char* kValidScene = R"({
  "dimension": 2,
  "effects": ["springs"],
  "nodes": {"positions": [[0, 0], [1.1, 0]], "masses": [1, 1]},
  "springs": [{"nodes": [0, 1], "model": "hookean", "stiffness": 1}],
  "pinned": [0]
})";

TEST_F(ProgramInput, BadFlags) {
  ExpectInputError("--no_such_flag=3", "flag", "--no_such_flag");
  ExpectInputError("--dt=abc", "flag", "--dt");
  ExpectInputError("--dt=-1", "flag", "--dt");
  ExpectInputError("--dt=nan", "flag", "--dt");
  ExpectInputError("--steps=-5", "flag", "--steps");
  ExpectInputError("--tolerance=0", "flag", "--tolerance");
  ExpectInputError("--optimizer=adam", "flag", "--optimizer");
  ExpectInputError("--integrator=rk4", "flag", "--integrator");
  ExpectInputError("--integrator=newmark --newmark_beta=0", "flag", "--newmark_beta");
  ExpectInputError("--integrator=newmark --newmark_gamma=2", "flag", "--newmark_gamma");
  ExpectInputError("--newmark_beta=0.3", "flag", "--newmark_beta");
  ExpectInputError("--integrator=newmark --newmark_beta=1e-300", "flag", "--newmark_beta");
  ExpectInputError("--integrator=newmark --newmark_gamma=0.4", "flag", "--newmark_gamma");
  ExpectInputError("--on_failure=maybe", "flag", "--on_failure");
  ExpectInputError("--linear_solver=MAGIC", "flag", "--linear_solver");
  ExpectInputError("--sparse_library=MKL", "flag", "--sparse_library");
  ExpectInputError("--optimizer=newton --line_search=ARMIJO", "flag", "--line_search");
  ExpectInputError("--optimizer=lbfgs --linear_solver=DENSE_QR", "flag", "--linear_solver");
  ExpectInputError("--optimizer=lbfgs --line_search=ARMIJO", "flag", "--line_search");
  ExpectInputError("--optimizer=lbfgs --backtrack_rejected_steps=false", "flag",
                   "--backtrack_rejected_steps");
  // projected_newton is neither Ceres family: both families' flags are errors.
  ExpectInputError("--optimizer=projected_newton --sparse_library=CX_SPARSE", "flag",
                   "--sparse_library");
  ExpectInputError("--optimizer=projected_newton --lbfgs_rank=3", "flag", "--lbfgs_rank");
  ExpectInputError("--max_iterations=-1", "flag", "--max_iterations");
  ExpectInputError("--frame_every=0", "flag", "--frame_every");
  ExpectInputError("--frames_format=binary", "flag", "--frames_format");
  ExpectInputError("--frames_precision=double", "flag", "--frames_precision");
  ExpectInputError("--grid_size=50", "flag", "--grid_size");  // oscillator has no grid
  ExpectInputError("--stats=/nonexistent_dir/x.csv", "flag", "--stats");
  ExpectInputError("stray_argument", "command line", "stray_argument");
  ExpectInputError("--scene=cloth --friction_mu=0.3", "flag", "--friction_mu");
  ExpectInputError("--scene=oscillator --contact_dhat=0.01", "flag", "--contact_dhat");
}

// Errors the library reports name its options ("options: OptimizerOptions.
// tolerance: ..."); the programs print them naming the flag, from one table
// (apps/flag_names.h), and never the library's name.
TEST_F(ProgramInput, LibraryErrorsNameTheFlag) {
  const struct {
    std::string arguments;
    std::string start;
  } cases[] = {
      {"--tolerance=0", "ipstep: error: flag: --tolerance: must be a finite number > 0"},
      {"--optimizer=adam", "ipstep: error: flag: --optimizer: unknown optimizer 'adam'"},
      {"--integrator=rk4", "ipstep: error: flag: --integrator: unknown integrator 'rk4'"},
      {"--integrator=newmark --newmark_beta=0",
       "ipstep: error: flag: --newmark_beta: must be in [1e-3, 1], got 0"},
      {"--integrator=newmark --newmark_gamma=2",
       "ipstep: error: flag: --newmark_gamma: must be in [0.5, 1], got 2"},
      {"--linear_solver=MAGIC", "ipstep: error: flag: --linear_solver: unknown linear solver"},
      {"--sparse_library=MKL", "ipstep: error: flag: --sparse_library: unknown sparse library"},
      {"--optimizer=lbfgs --line_search=GOLDEN",
       "ipstep: error: flag: --line_search: unknown line search 'GOLDEN'"},
      {"--optimizer=ncg --nonlinear_cg=DAI_YUAN",
       "ipstep: error: flag: --nonlinear_cg: unknown type 'DAI_YUAN'"},
      {"--optimizer=lbfgs --line_search=ARMIJO",
       "ipstep: error: flag: --line_search: invalid Ceres options for lbfgs"},
      {"--grid_size=50", "ipstep: error: flag: --grid_size: scene "},
      {"--scene=cloth_sphere --grid_size=100 --optimizer=bfgs --steps=1",
       "ipstep: error: flag: --optimizer=bfgs: BFGS stores a dense matrix"},
      {"--optimizer=projected_newton --hessian_projection=sometimes",
       "ipstep: error: flag: --hessian_projection: unknown projection 'sometimes'"},
      {"--hessian_projection=when_indefinite",
       "ipstep: error: flag: --hessian_projection: when_indefinite needs the assembled Hessian: "
       "projected_newton only (newton takes always, abs, trust_region or inertia)"},
      {"--optimizer=dogleg --hessian_projection=progressive",
       "ipstep: error: flag: --hessian_projection: progressive needs the assembled Hessian"},
      {"--optimizer=lbfgs --hessian_projection=abs",
       "ipstep: error: flag: --hessian_projection: applies to newton, dogleg and "
       "projected_newton, not to --optimizer=lbfgs"},
      {"--optimizer=projected_newton --sparse_library=CX_SPARSE",
       "ipstep: error: flag: --sparse_library: projected_newton uses SUITE_SPARSE (CHOLMOD) or "
       "EIGEN_SPARSE, not 'CX_SPARSE'"},
      {"--linear_solver_ordering=METIS",
       "ipstep: error: flag: --linear_solver_ordering: unknown ordering 'METIS' (AMD or NESDIS)"},
      {"--stats=/nonexistent_dir/x.csv",
       "ipstep: error: flag: --stats: cannot write '/nonexistent_dir/x.csv'"},
      // Opened before the run: the error comes before any report.
      {"--steps=1 --positions=/nonexistent_dir/x.csv",
       "ipstep: error: flag: --positions: cannot write '/nonexistent_dir/x.csv'"},
      {"--iterations_log=/nonexistent_dir/x.csv",
       "ipstep: error: flag: --iterations_log: cannot write '/nonexistent_dir/x.csv'"},
      {"--frames=/dev/null/frames",
       "ipstep: error: flag: --frames: cannot create directory '/dev/null/frames'"},
  };
  for (const auto& c : cases) {
    ExpectInputError(c.arguments, "flag", "--");
    const Outcome o = RunIpstep(c.arguments);
    EXPECT_EQ(o.output.rfind(c.start, 0), 0u) << c.arguments << "\n" << o.output;
    EXPECT_EQ(o.output.find("Options."), std::string::npos) << o.output;
    EXPECT_EQ(o.output.find("output:"), std::string::npos) << o.output;
  }
  // The explicit alternative is an integrator, named as its flag would be given.
  const Outcome beta = RunIpstep("--integrator=newmark --newmark_beta=0");
  EXPECT_NE(beta.output.find("use the integrator symplectic_euler"), std::string::npos)
      << beta.output;
  // ipstep_compare: the same names; an integrator's bad parameter is not an
  // unknown integrator of --integrators.
  const Outcome compare = ipstep::testing::RunProgram(
      IPSTEP_COMPARE_BINARY, "--integrator=newmark --newmark_beta=0 --integrators=newmark");
  EXPECT_EQ(compare.exit_code, 2) << compare.output;
  EXPECT_EQ(compare.output.rfind("ipstep_compare: error: flag: --newmark_beta: must be in", 0), 0u)
      << compare.output;
  const Outcome tolerance = ipstep::testing::RunProgram(IPSTEP_COMPARE_BINARY, "--tolerance=-1");
  EXPECT_EQ(tolerance.output.rfind("ipstep_compare: error: flag: --tolerance: must be", 0), 0u)
      << tolerance.output;
}

// An unset flag means the default; an explicit 0 (or -1) is a value, and out
// of range. Every size-like flag has an upper bound (core/input_limits.h).
TEST_F(ProgramInput, ExplicitSentinelsAndHugeValuesAreErrors) {
  for (const char* arguments : {"--dt=0",
                                "--steps=-1",
                                "--max_iterations=0",
                                "--time_limit=0",
                                "--trust_region_radius=0",
                                "--optimizer=lbfgs --lbfgs_rank=0",
                                "--scene=cloth --grid_size=0",
                                "--num_threads=0",
                                "--optimizer=lbfgs --lbfgs_rank=2147483647",
                                "--max_iterations=2147483647",
                                "--steps=2147483647",
                                "--num_threads=100000",
                                "--scene=cloth --grid_size=2147483647",
                                "--frame_every=2147483647",
                                "--dt=1e-13",
                                "--dt=1e4",
                                "--time_limit=1e308",
                                "--time_limit=inf",
                                "--trust_region_radius=1e300",
                                "--trust_region_radius=1e-300",
                                "--tolerance=inf"}) {
    const std::string text = arguments;
    const size_t flag = text.rfind("--");
    ExpectInputError(text, "flag", text.substr(flag, text.find('=', flag) - flag));
  }
  const Outcome o = RunIpstep("--dt=0");
  EXPECT_NE(o.output.find("flag: --dt: must be in [1e-12, 1e3] s (omit the flag for the scene's "
                          "time_step), got 0"),
            std::string::npos)
      << o.output;
  const Outcome rank = RunIpstep("--optimizer=lbfgs --lbfgs_rank=2147483647");
  EXPECT_NE(rank.output.find("[1, 1000]"), std::string::npos) << rank.output;
  // In range: runs.
  for (const char* arguments :
       {"--dt=1e-6 --steps=2", "--steps=0", "--max_iterations=1 --on_failure=continue --steps=2",
        "--time_limit=1e9 --steps=2", "--trust_region_radius=1e-12 --steps=2",
        "--optimizer=lbfgs --lbfgs_rank=1000 --steps=2", "--scene=cloth --grid_size=2 --steps=2",
        "--num_threads=2 --steps=2", "--frame_every=10000000 --steps=2"}) {
    const Outcome ok = RunIpstep(arguments);
    EXPECT_EQ(ok.exit_code, 0) << arguments << "\n" << ok.output;
  }
}

TEST_F(ProgramInput, CompareFlagsFollowTheContract) {
  const auto run = [](const std::string& arguments) {
    return ipstep::testing::RunProgram(IPSTEP_COMPARE_BINARY, arguments);
  };
  for (const char* arguments :
       {"--dt=0", "--steps=-1", "--max_iterations=0", "--steps=2147483647",
        "--integrators=", "--optimizers=,", "--integrators=rk4", "--optimizers=adam",
        "--integrator=newmark --newmark_beta=1e-300", "--no_such_flag"}) {
    const Outcome o = run(arguments);
    EXPECT_EQ(o.exit_code, 2) << arguments << "\n" << o.output;
    EXPECT_EQ(o.output.rfind("ipstep_compare: error: flag: --", 0), 0u) << arguments << o.output;
    EXPECT_EQ(std::count(o.output.begin(), o.output.end(), '\n'), 1) << o.output;
  }
  const Outcome ok = run("--steps=2 --integrators=backward_euler --optimizers=newton");
  EXPECT_EQ(ok.exit_code, 0) << ok.output;
}

// gflags' own flags follow the contract too: help variants exit 0; flags from
// a flagfile or the environment are checked like the command line's.
TEST_F(ProgramInput, GflagsOwnFlags) {
  for (const std::string help : {"--help", "--helpfull", "--helpshort", "--helppackage",
                                 "--helpon=solver_flags", "--helpmatch=solver", "--helpxml"}) {
    const Outcome o = RunIpstep(help);
    EXPECT_EQ(o.exit_code, 0) << help << "\n" << o.output.substr(0, 300);
    EXPECT_NE(o.output.find("dt"), std::string::npos) << help << "\n" << o.output.substr(0, 300);
  }
  const Outcome version = RunIpstep("--version");
  EXPECT_EQ(version.exit_code, 0) << version.output;
  EXPECT_EQ(version.output.rfind("ipstep", 0), 0u) << version.output;
  EXPECT_NE(RunIpstep("--helpshort").output.find("frame_every"), std::string::npos);
  EXPECT_EQ(RunIpstep("--helpshort").output.find("logtostderr"), std::string::npos);

  // --flagfile: every line is checked; where it came from is named.
  const std::string good =
      Write("good.flags", "# comment\n\n  --dt=0.05\n--steps=2\n--noprogress\n");
  const Outcome applied = RunIpstep("--flagfile=" + good);
  EXPECT_EQ(applied.exit_code, 0) << applied.output;
  EXPECT_NE(applied.output.find("dt 0.05 s, 2 steps"), std::string::npos) << applied.output;
  const Outcome two_tokens = RunIpstep("--flagfile " + good + " --steps=3");
  EXPECT_NE(two_tokens.output.find("dt 0.05 s, 3 steps"), std::string::npos) << two_tokens.output;
  const std::string unknown = Write("unknown.flags", "--dt=0.05\n--no_such_flag=1\n");
  ExpectInputError("--flagfile=" + unknown, "--no_such_flag", "unknown.flags, line 2");
  ExpectInputError("--flagfile=" + Write("zero.flags", "--dt=0\n"), "--dt", "zero.flags, line 1");
  ExpectInputError("--flagfile=" + Write("value.flags", "--dt\n"), "--dt", "missing value");
  ExpectInputError("--flagfile=" + Write("section.flags", "ipstep\n--dt=1\n"), "--flagfile",
                   "section.flags, line 1");
  ExpectInputError("--flagfile=" + (dir_ / "missing.flags").string(), "--flagfile",
                   "missing.flags");
  ExpectInputError("--flagfile=/dev/zero", "--flagfile", "not a regular file");
  const std::string loop = (dir_ / "loop.flags").string();
  Write("loop.flags", "--flagfile=" + loop + "\n");
  ExpectInputError("--flagfile=" + loop, "--flagfile", "nested");
  ExpectInputError("--flagfile", "--flagfile", "missing value");

  // --fromenv / --tryfromenv read FLAGS_<name>.
  const auto with_env = [](const std::string& env, const std::string& arguments) {
    return ipstep::testing::RunProgram(env + " " + IPSTEP_BINARY, arguments);
  };
  Outcome o = with_env("FLAGS_dt=0.05", "--fromenv=dt --steps=1");
  EXPECT_EQ(o.exit_code, 0) << o.output;
  EXPECT_NE(o.output.find("dt 0.05 s"), std::string::npos) << o.output;
  o = with_env("FLAGS_dt=0", "--tryfromenv=dt");
  EXPECT_EQ(o.exit_code, 2) << o.output;
  EXPECT_NE(o.output.find("--dt: must be in"), std::string::npos) << o.output;
  EXPECT_NE(o.output.find("FLAGS_dt"), std::string::npos) << o.output;
  o = with_env("FLAGS_dt=abc", "--fromenv=dt");
  EXPECT_EQ(o.exit_code, 2) << o.output;
  EXPECT_EQ(std::count(o.output.begin(), o.output.end(), '\n'), 1) << o.output;
  ExpectInputError("--fromenv=ipstep_test_unset_flag", "--fromenv", "ipstep_test_unset_flag");
  o = with_env("env -u FLAGS_steps", "--fromenv=steps");
  EXPECT_EQ(o.exit_code, 2) << o.output;
  EXPECT_NE(o.output.find("FLAGS_steps is not set"), std::string::npos) << o.output;
  o = with_env("env -u FLAGS_steps", "--tryfromenv=steps --steps=1");
  EXPECT_EQ(o.exit_code, 0) << o.output;
  ExpectInputError("--undefok=foo", "--undefok", "not supported");
}

#ifdef IPSTEP_BENCH_BINARY
// ipstep_bench has its own flags but the same contract.
TEST_F(ProgramInput, BenchFlagsFollowTheContract) {
  const auto run = [](const std::string& arguments) {
    return ipstep::testing::RunProgram(IPSTEP_BENCH_BINARY, arguments);
  };
  const std::string flagfile = Write("bench.flags", "--repeats=1\n--bogus=1\n");
  for (const std::string& arguments :
       std::vector<std::string>{"--steps=0",
                                "--t_end=0",
                                "--repeats=0",
                                "--repeats=2147483647",
                                "--warmup=2147483647",
                                "--steps=2147483647",
                                "--t_end=1e300",
                                "--dts=1e-300",
                                "--dts=1e300",
                                "--dt_factors=1e-300",
                                "--grid_sizes=0",
                                "--grid_sizes=2147483647",
                                "--optimizers=newton+radius=0",
                                "--optimizers=lbfgs+rank=2147483647",
                                "--optimizers=newton+threads=100000",
                                "--optimizers=newton+max_iterations=2147483647",
                                "--max_run_seconds=-1",
                                "--max_run_seconds=1e300",
                                "--reference_tolerance=0",
                                "--tolerances=inf",
                                "--merge=/dev/zero",
                                "--flagfile=" + flagfile,
                                "--undefok=x",
                                "--no_such_flag"}) {
    const Outcome o = run(arguments + " --dry_run --output=" + (dir_ / "out.csv").string());
    EXPECT_EQ(o.exit_code, 2) << arguments << "\n" << o.output;
    EXPECT_EQ(o.output.rfind("ipstep_bench: error: ", 0), 0u) << arguments << "\n" << o.output;
    EXPECT_EQ(std::count(o.output.begin(), o.output.end(), '\n'), 1) << o.output;
  }
  for (const char* help : {"--help", "--helpshort", "--version"}) {
    const Outcome o = run(help);
    EXPECT_EQ(o.exit_code, 0) << help << "\n" << o.output.substr(0, 300);
  }
  EXPECT_NE(run("--helpshort").output.find("repeats"), std::string::npos);
  // An item the library rejects names the list flag ipstep_bench has, and the item.
  for (const auto& [arguments, start] : std::vector<std::pair<std::string, std::string>>{
           {"--optimizers=newton+sparse=MKL",
            "ipstep_bench: error: flag: --optimizers: 'newton+sparse=MKL': unknown sparse library "
            "'MKL'"},
           {"--optimizers=adam",
            "ipstep_bench: error: flag: --optimizers: 'adam': unknown optimizer"},
           {"--integrators=rk4",
            "ipstep_bench: error: flag: --integrators: 'rk4': unknown integrator 'rk4'"}}) {
    const Outcome o = run(arguments + " --dry_run --output=" + (dir_ / "out.csv").string());
    EXPECT_EQ(o.exit_code, 2) << arguments << "\n" << o.output;
    EXPECT_EQ(o.output.rfind(start, 0), 0u) << arguments << "\n" << o.output;
  }
  // A run that blows up is "diverged" in the CSV, with no drift or error value.
  const std::string csv = (dir_ / "diverged.csv").string();
  const Outcome blown =
      run("--scenes=cloth --grid_sizes=6 --integrators=symplectic_euler --steps=20 --repeats=1 "
          "--warmup=0 --output=" +
          csv);
  ASSERT_EQ(blown.exit_code, 0) << blown.output;
  std::ifstream in(csv);
  std::string header, row;
  std::getline(in, header);
  std::getline(in, row);
  EXPECT_NE(row.find(",diverged at step "), std::string::npos) << row;
  // No huge number in the row (the commit column, last, may hold "e+" in
  // "<hash>+changes").
  EXPECT_EQ(row.substr(0, row.rfind(',')).find("e+"), std::string::npos) << row;
  const Outcome ok = run("--grid_sizes=scene,4 --scenes=cloth --steps=3 --dry_run");
  EXPECT_EQ(ok.exit_code, 0) << ok.output;
  EXPECT_NE(ok.output.find("grid=0"), std::string::npos) << ok.output;
  EXPECT_NE(ok.output.find("grid=4"), std::string::npos) << ok.output;
}
#endif

// Help finds the programs' own flags first, grouped, with the built-in scenes;
// glog's flags only with --helpfull.
TEST_F(ProgramInput, HelpShowsTheProgramsFlagsGrouped) {
  for (const char* help : {"--help", "--helpshort"}) {
    const Outcome o = RunIpstep(help);
    ASSERT_EQ(o.exit_code, 0) << o.output;
    size_t last = 0;
    for (const char* group : {"\nScene:", "\nIntegrator, failed steps and adaptive steps:",
                              "\nOptimiser:", "\nContact (", "\nOutput:"}) {
      const size_t at = o.output.find(group);
      EXPECT_NE(at, std::string::npos) << help << ": " << group << "\n" << o.output;
      EXPECT_GT(at, last) << help << ": " << group << " out of order";
      last = at;
    }
    for (const char* flag : {"-scene ", "-integrator ", "-optimizer ", "-tolerance ", "-dt ",
                             "-contact_kappa ", "-stats ", "-frames "}) {
      EXPECT_NE(o.output.find(flag), std::string::npos) << help << ": " << flag;
    }
    for (const char* scene : {"oscillator", "cloth_sphere", "two_squares", "drop"}) {
      EXPECT_NE(o.output.find(scene), std::string::npos) << help << ": " << scene;
    }
    EXPECT_EQ(o.output.find("logtostderr"), std::string::npos) << help;
    EXPECT_NE(o.output.find("--helpfull"), std::string::npos) << help;
  }
  const Outcome full = RunIpstep("--helpfull");
  EXPECT_EQ(full.exit_code, 0);
  EXPECT_NE(full.output.find("logtostderr"), std::string::npos);
  EXPECT_LT(full.output.find("-scene "), full.output.find("logtostderr"));
  const Outcome compare = ipstep::testing::RunProgram(IPSTEP_COMPARE_BINARY, "--help");
  // ipstep_compare's lists in their groups.
  EXPECT_GT(compare.output.find("-integrators "), compare.output.find("\nIntegrator"))
      << compare.output;
  EXPECT_GT(compare.output.find("-optimizers "), compare.output.find("\nOptimiser:"))
      << compare.output;
  EXPECT_NE(compare.output.find("-optimizers "), std::string::npos) << compare.output;
}

TEST_F(ProgramInput, VersionIsTheProjectVersion) {
  const Outcome o = RunIpstep("--version");
  EXPECT_EQ(o.exit_code, 0);
  EXPECT_EQ(o.output, std::string("ipstep ") + IPSTEP_VERSION + "\n");
  const Outcome compare = ipstep::testing::RunProgram(IPSTEP_COMPARE_BINARY, "--version");
  EXPECT_EQ(compare.output, std::string("ipstep_compare ") + IPSTEP_VERSION + "\n");
}

// A near miss of a flag's name gets a suggestion; a bad list item names the
// list flag.
TEST_F(ProgramInput, NearMissesAreSuggested) {
  ExpectInputError("--optimiser=ncg", "--optimiser", "did you mean --optimizer?");
  ExpectInputError("--tolerence=1e-3", "--tolerence", "did you mean --tolerance?");
  ExpectInputError("--sene=cloth", "--sene", "did you mean --scene?");
  const Outcome far = RunIpstep("--completely_unrelated=1");
  EXPECT_EQ(far.exit_code, 2);
  EXPECT_EQ(far.output.find("did you mean"), std::string::npos) << far.output;
  const auto compare = [](const std::string& arguments) {
    return ipstep::testing::RunProgram(IPSTEP_COMPARE_BINARY, arguments);
  };
  Outcome o = compare("--optimizers=newton,newtn");
  EXPECT_EQ(o.exit_code, 2) << o.output;
  EXPECT_EQ(o.output.rfind("ipstep_compare: error: flag: --optimizers: unknown optimizer 'newtn' "
                           "(did you mean newton?)",
                           0),
            0u)
      << o.output;
  o = compare("--integrators=newmrk");
  EXPECT_EQ(o.exit_code, 2) << o.output;
  EXPECT_EQ(o.output.rfind("ipstep_compare: error: flag: --integrators: unknown integrator "
                           "'newmrk' (did you mean newmark?)",
                           0),
            0u)
      << o.output;
}

// Ceres's warnings (here nonlinear CG's restarts) stay out of a normal run;
// -v=1 brings them back.
TEST_F(ProgramInput, CeresWarningsOnlyWhenAsked) {
  const std::string args =
      "--scene=cloth --grid_size=8 --optimizer=ncg --steps=3 --on_failure=continue";
  const Outcome quiet = RunIpstep(args);
  EXPECT_EQ(quiet.exit_code, 0) << quiet.output;
  EXPECT_EQ(quiet.output.find("Restarting"), std::string::npos) << quiet.output;
  EXPECT_EQ(quiet.output.find("W1"), std::string::npos) << quiet.output;  // glog's W<mmdd> prefix
  const Outcome verbose = RunIpstep(args + " -v=1");
  EXPECT_NE(verbose.output.find("Restarting non-linear conjugate gradients"), std::string::npos)
      << verbose.output.substr(0, 2000);
}

// ipstep_compare: one progress line per configuration on stderr, the table on
// stdout, and a run that blows up is "diverged", not a number.
TEST_F(ProgramInput, CompareReportsProgressAndDivergence) {
  const std::string args =
      "--scene=cloth --grid_size=6 --steps=20 --integrators=backward_euler,symplectic_euler "
      "--optimizers=newton,lbfgs";
  const Outcome stdout_only = ipstep::testing::RunProgram(
      std::string(IPSTEP_COMPARE_BINARY) + " " + args + " 2>/dev/null; exit $?", "");
  const Outcome both = ipstep::testing::RunProgram(IPSTEP_COMPARE_BINARY, args);
  ASSERT_EQ(both.exit_code, 0) << both.output;
  for (const char* line : {"[1/3] backward_euler newton", "[2/3] backward_euler lbfgs",
                           "[3/3] symplectic_euler (explicit)"}) {
    EXPECT_NE(both.output.find(line), std::string::npos) << line << "\n" << both.output;
    EXPECT_EQ(stdout_only.output.find(line), std::string::npos) << stdout_only.output;
  }
  EXPECT_NE(stdout_only.output.find("| symplectic_euler | (explicit) |"), std::string::npos);
  EXPECT_NE(stdout_only.output.find("| diverged (step "), std::string::npos) << stdout_only.output;
  EXPECT_NE(stdout_only.output.find("diverged: a position, velocity or energy became non-finite"),
            std::string::npos);
  EXPECT_EQ(stdout_only.output.find("e+"), std::string::npos) << stdout_only.output;
}

TEST_F(ProgramInput, BadSceneFiles) {
  ExpectInputError("--scene=" + (dir_ / "missing.json").string(), "missing.json", "");
  ExpectInputError("--scene=no_such_builtin", "no_such_builtin", "oscillator");
  const std::string malformed = Write("malformed.json", "{\"dimension\": 2,, }");
  ExpectInputError("--scene=" + malformed, "malformed.json", "");
  std::string text = kValidScene;
  const std::string unknown = Write("unknown.json", text.replace(1, 0, "\"colour\": 1,"));
  ExpectInputError("--scene=" + unknown, "unknown.json", "colour");
  text = kValidScene;
  const std::string mass = Write("mass.json", text.replace(text.find("[1, 1]"), 6, "[1, -1]"));
  ExpectInputError("--scene=" + mass, "mass.json", "masses");
  text = kValidScene;
  const std::string index = Write("index.json", text.replace(text.find("[0, 1]"), 6, "[0, 7]"));
  ExpectInputError("--scene=" + index, "index.json", "springs[0]");
  text = kValidScene;
  const std::string type =
      Write("type.json", text.replace(text.find("\"stiffness\": 1"), 14, "\"stiffness\": \"1\""));
  ExpectInputError("--scene=" + type, "type.json", "stiffness");
}

TEST_F(ProgramInput, SceneFilesAreRegularBoundedAndWhole) {
  ExpectInputError("--scene=/dev/zero", "/dev/zero", "not a regular file");
  ExpectInputError("--scene=" + dir_.string(), dir_.string(), "directory");
  std::string text = kValidScene;
  text += std::string(1, '\0') + "garbage";
  ExpectInputError("--scene=" + Write("nul.json", text), "nul.json", "NUL byte");
  ExpectInputError("--scene=" + Write("trailing.json", std::string(kValidScene) + " 1"),
                   "trailing.json", "malformed JSON");
  // A 10 MB unknown key: one short line.
  text = kValidScene;
  const std::string key(10 << 20, 'x');
  const Outcome o =
      RunIpstep("--scene=" + Write("key.json", text.replace(1, 0, "\"" + key + "\": 1,")));
  EXPECT_EQ(o.exit_code, 2) << o.output.substr(0, 300);
  EXPECT_LT(o.output.size(), 400u) << o.output.substr(0, 400);
  EXPECT_NE(o.output.find("unknown key"), std::string::npos) << o.output.substr(0, 400);
}

TEST_F(ProgramInput, ValidRunWritesItsOutputs) {
  const std::string scene = Write("ok.json", kValidScene);
  const std::string stats = (dir_ / "stats.csv").string();
  const std::string log = (dir_ / "iterations.csv").string();
  const std::string positions = (dir_ / "positions.csv").string();
  const std::string frames = (dir_ / "frames").string();
  const Outcome o = RunIpstep("--scene=" + scene + " --dt=0.1 --steps=4 --stats=" + stats +
                              " --iterations_log=" + log + " --positions=" + positions +
                              " --frames=" + frames + " --frame_every=2");
  ASSERT_EQ(o.exit_code, 0) << o.output;
  EXPECT_NE(o.output.find("springs: 1 hookean"), std::string::npos) << o.output;
  std::ifstream in(stats);
  std::string header;
  std::getline(in, header);
  for (const char* column : {"step", "time", "iterations", "converged", "wall_seconds",
                             "kinetic_energy", "potential_energy", "total_energy", "residual"}) {
    EXPECT_NE(header.find(column), std::string::npos) << column;
  }
  int rows = 0;
  for (std::string line; std::getline(in, line);) ++rows;
  EXPECT_EQ(rows, 4);
  std::ifstream p(positions);
  std::string first;
  std::getline(p, first);
  EXPECT_EQ(first, "node,x,y");
  EXPECT_TRUE(fs::exists(fs::path(frames) / "run.pvd"));
  EXPECT_TRUE(fs::exists(fs::path(frames) / "frame_00000.vtu"));
  EXPECT_TRUE(fs::exists(fs::path(frames) / "frame_00004.vtu"));
  EXPECT_FALSE(fs::exists(fs::path(frames) / "frame_00003.vtu"));
  std::ifstream l(log);
  std::getline(l, header);
  EXPECT_EQ(header, "step,iteration,energy,gradient_norm,step_size,seconds,residual");
}

TEST_F(ProgramInput, FailedStepStopsWithExitCodeThree) {
  const Outcome o =
      RunIpstep("--scene=cloth --optimizer=gradient_descent --max_iterations=2 --steps=3");
  EXPECT_EQ(o.exit_code, 3) << o.output;
  EXPECT_NE(o.output.find("iteration limit (2)"), std::string::npos) << o.output;
  const Outcome c = RunIpstep(
      "--scene=cloth --optimizer=gradient_descent --max_iterations=2 --steps=2 "
      "--on_failure=continue");
  EXPECT_EQ(c.exit_code, 0) << c.output;
  EXPECT_NE(c.output.find("2 failed"), std::string::npos) << c.output;
}

// Symplectic Euler past its stability limit (the cloth at its own 1/60 s): the
// run is diverged (sim/divergence.h), never "converged" while its energy grows.
// It stops there with exit code 3; with --on_failure=continue every later step
// says "diverged" in the stats and the summary counts them as failed.
TEST_F(ProgramInput, DivergedStepsAreNotConverged) {
  const std::string stats = (dir_ / "diverged_stats.csv").string();
  const Outcome stop = RunIpstep(
      "--scene=cloth --grid_size=6 --integrator=symplectic_euler "
      "--steps=40 --stats=" +
      stats);
  EXPECT_EQ(stop.exit_code, 3) << stop.output;
  EXPECT_NE(stop.output.find(", diverged at step "), std::string::npos) << stop.output;
  EXPECT_NE(stop.output.find("stopping (--on_failure=stop): diverged at step "), std::string::npos)
      << stop.output;
  const Outcome go = RunIpstep(
      "--scene=cloth --grid_size=6 --integrator=symplectic_euler "
      "--steps=40 --on_failure=continue --stats=" +
      stats);
  EXPECT_EQ(go.exit_code, 0) << go.output;
  std::ifstream in(stats);
  std::string line;
  std::getline(in, line);
  int rows = 0, diverged = 0, converged_after = 0;
  while (std::getline(in, line)) {
    ++rows;
    const bool is_diverged = line.find("diverged: ") != std::string::npos;
    if (is_diverged || diverged > 0) {
      diverged += is_diverged;
      converged_after += line.find(",1,\"") != std::string::npos;  // converged, status
    }
  }
  EXPECT_EQ(rows, 40);
  EXPECT_GT(diverged, 0);
  EXPECT_EQ(converged_after, 0);
  EXPECT_NE(go.output.find(std::to_string(diverged) + " failed"), std::string::npos) << go.output;
}

// --t_end: the steps follow from it; a t_end that is no whole number of steps
// names a step that fits; not with --steps.
TEST_F(ProgramInput, EndTimeSetsTheSteps) {
  const Outcome o = RunIpstep("--scene=oscillator --dt=0.1 --t_end=0.5");
  EXPECT_EQ(o.exit_code, 0) << o.output;
  EXPECT_NE(o.output.find("done: 5 steps"), std::string::npos) << o.output;
  ExpectInputError("--scene=oscillator --dt=0.1 --t_end=0.55", "--t_end", "a step that fits: ");
  ExpectInputError("--scene=oscillator --steps=3 --t_end=0.5", "--t_end", "not both");
  ExpectInputError("--scene=oscillator --t_end=-1", "--t_end", "");
}

// --adaptive: the steps follow from --error_tolerance; its flags are errors
// without it, and --steps and --max_substeps are errors with it.
TEST_F(ProgramInput, AdaptiveRunsAndItsFlagsFollowTheContract) {
  const std::string stats = (dir_ / "adaptive.csv").string();
  const Outcome o = RunIpstep(
      "--scene=oscillator --integrator=newmark --adaptive "
      "--error_tolerance=1e-4 --t_end=5 --stats=" +
      stats);
  EXPECT_EQ(o.exit_code, 0) << o.output;
  EXPECT_NE(o.output.find("adaptive steps to t = 5 s for an error of 0.0001 m"), std::string::npos)
      << o.output;
  EXPECT_NE(o.output.find("; adaptive: "), std::string::npos) << o.output;
  std::ifstream in(stats);
  std::string header;
  std::getline(in, header);
  EXPECT_NE(header.find(",time_step,error_estimate,rejected"), std::string::npos) << header;
  ExpectInputError("--scene=oscillator --error_tolerance=1e-4", "--error_tolerance",
                   "with --adaptive only");
  ExpectInputError("--scene=oscillator --max_dt=0.1", "--max_dt", "with --adaptive only");
  ExpectInputError("--scene=oscillator --adaptive --steps=10", "--steps", "--t_end");
  ExpectInputError("--scene=oscillator --adaptive --max_substeps=4", "--max_substeps", "");
  ExpectInputError("--scene=oscillator --adaptive --error_tolerance=0", "--error_tolerance", "");
  ExpectInputError("--scene=oscillator --adaptive --min_dt=0.1 --max_dt=0.01", "--min_dt", "");
  ExpectInputError("--scene=oscillator --adaptive --integrator=quasi_static", "--adaptive",
                   "dynamic integrator");
}

// ipstep_tune on the oscillator (exact solution): it recommends a run within
// the target, and that command line, run, is within it.
TEST_F(ProgramInput, TuneRecommendsARunThatReachesTheTarget) {
  const Outcome o =
      ipstep::testing::RunProgram(std::string(IPSTEP_TUNE_BINARY) +
                                      " --scene=oscillator --target_error=1e-3 2>/dev/null; "
                                      "exit $?",
                                  "");
  ASSERT_EQ(o.exit_code, 0) << o.output;
  const size_t at = o.output.find("\n  ipstep ");
  ASSERT_NE(at, std::string::npos) << o.output;
  const std::string command = o.output.substr(at + 9, o.output.find('\n', at + 3) - at - 9);
  const std::string positions = (dir_ / "tuned.csv").string();
  const Outcome run = RunIpstep(command + " --positions=" + positions);
  ASSERT_EQ(run.exit_code, 0) << command << "\n" << run.output;
  std::ifstream in(positions);
  std::string line;
  std::getline(in, line);  // header
  std::getline(in, line);  // node 0 (pinned)
  std::getline(in, line);  // node 1
  const double x = std::stod(line.substr(line.find(',') + 1));
  EXPECT_LE(std::abs(x - (1.0 + 0.1 * std::cos(10.0))), 1e-3) << command;
  const Outcome bad = ipstep::testing::RunProgram(
      std::string(IPSTEP_TUNE_BINARY) + " --scene=oscillator --target_error=0", "");
  EXPECT_EQ(bad.exit_code, 2) << bad.output;
  EXPECT_NE(bad.output.find("--target_error"), std::string::npos) << bad.output;
}

// --match_default: the target is the default configuration's own measured
// error (backward Euler at h = 0.1 s on the oscillator: |x - (1 + 0.1 cos 10)|
// at t = 10 s), and the recommendation, run, is within it.
TEST_F(ProgramInput, TuneMatchDefaultTargetsTheDefaultsOwnError) {
  const Outcome o = ipstep::testing::RunProgram(
      std::string(IPSTEP_TUNE_BINARY) + " --scene=oscillator --match_default 2>/dev/null; exit $?",
      "");
  ASSERT_EQ(o.exit_code, 0) << o.output;
  const std::string prefix = "error target ";
  const size_t at = o.output.find(prefix);
  ASSERT_NE(at, std::string::npos) << o.output;
  const double target = std::stod(o.output.substr(at + prefix.size()));
  EXPECT_NE(o.output.find("m (the default's error)"), std::string::npos) << o.output;
  // x at t = 10 s of an ipstep run, node 1's first coordinate.
  auto final_x = [this](const std::string& arguments) {
    const std::string positions = (dir_ / "run.csv").string();
    const Outcome run = RunIpstep(arguments + " --positions=" + positions);
    EXPECT_EQ(run.exit_code, 0) << arguments << "\n" << run.output;
    std::ifstream in(positions);
    std::string line;
    for (int k = 0; k < 3; ++k) std::getline(in, line);  // header, node 0, node 1
    return std::stod(line.substr(line.find(',') + 1));
  };
  const double exact = 1.0 + 0.1 * std::cos(10.0);
  const double error = std::abs(final_x("--scene=oscillator") - exact);  // the default
  EXPECT_NEAR(target, error, 1e-3 * error) << o.output;
  const size_t command = o.output.find("\n  ipstep ");
  ASSERT_NE(command, std::string::npos) << o.output;
  const std::string recommended =
      o.output.substr(command + 9, o.output.find('\n', command + 3) - command - 9);
  EXPECT_LE(std::abs(final_x(recommended) - exact), target) << recommended;
  const Outcome both = ipstep::testing::RunProgram(
      std::string(IPSTEP_TUNE_BINARY) + " --scene=oscillator --match_default --target_error=1", "");
  EXPECT_EQ(both.exit_code, 2) << both.output;
  EXPECT_NE(both.output.find("--match_default"), std::string::npos) << both.output;
}

// --tune_output: every run of the search, then the second runs of the pick
// and the default (role timing) and the default; exactly one pick, whose
// configuration is the recommended command line's, and the default is
// backward Euler x newton at the scene's step with the default tolerance.
TEST_F(ProgramInput, TuneOutputMarksThePickTheDefaultAndTheirSecondRuns) {
  const std::string csv = (dir_ / "tune.csv").string();
  const Outcome o = ipstep::testing::RunProgram(std::string(IPSTEP_TUNE_BINARY) +
                                                    " --scene=oscillator --target_error=1e-3 "
                                                    "--tune_output=" +
                                                    csv + " 2>/dev/null; exit $?",
                                                "");
  ASSERT_EQ(o.exit_code, 0) << o.output;
  std::ifstream in(csv);
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line,
            "integrator,optimizer,adaptive,dt,tolerance,error_tolerance,steps,failed,iterations,"
            "seconds,error,role,family,position,shard,target,out_of_time,search");
  std::vector<std::vector<std::string>> rows;
  while (std::getline(in, line)) {
    std::vector<std::string> fields;
    std::stringstream split(line);
    for (std::string field; std::getline(split, field, ',');) fields.push_back(field);
    ASSERT_EQ(fields.size(), 18u) << line;
    rows.push_back(fields);
  }
  ASSERT_GE(rows.size(), 4u);
  int picks = 0;
  std::vector<std::string> pick;
  for (size_t k = 0; k + 3 < rows.size(); ++k) {
    EXPECT_TRUE(rows[k][11] == "search" || rows[k][11] == "pick") << rows[k][11];
    if (rows[k][11] == "pick") {
      ++picks;
      pick = rows[k];
    }
  }
  ASSERT_EQ(picks, 1);
  const std::vector<std::string>& pick_again = rows[rows.size() - 3];
  const std::vector<std::string>& default_again = rows[rows.size() - 2];
  const std::vector<std::string>& fallback = rows.back();
  EXPECT_EQ(pick_again[11], "timing");
  EXPECT_EQ(default_again[11], "timing");
  EXPECT_EQ(fallback[11], "default");
  for (int field : {0, 1, 2, 3, 4, 5, 6, 8, 10}) {  // all but failed, seconds, role
    EXPECT_EQ(pick_again[field], pick[field]) << field;
    EXPECT_EQ(default_again[field], fallback[field]) << field;
  }
  EXPECT_EQ(
      fallback[0] + "," + fallback[1] + "," + fallback[2] + "," + fallback[3] + "," + fallback[4],
      "backward_euler,newton,0,0.1,1e-05");
  EXPECT_NE(o.output.find("--integrator=" + pick[0] + " --optimizer=" + pick[1]), std::string::npos)
      << o.output;
}

TEST_F(ProgramInput, EveryIntegratorAndOptimizerRunsEveryBuiltinScene) {
  for (const char* scene : {"oscillator", "spring_pendulum", "cloth", "fpu", "hanging_square"}) {
    for (const char* integrator :
         {"backward_euler", "newmark", "quasi_static", "symplectic_euler"}) {
      for (const char* optimizer : {"newton", "dogleg", "gauss_newton", "lbfgs", "bfgs", "ncg",
                                    "gradient_descent", "projected_newton"}) {
        std::ostringstream args;
        args << "--scene=" << scene << " --integrator=" << integrator
             << " --optimizer=" << optimizer << " --steps=2 --on_failure=continue";
        if (std::string(scene) == "cloth") args << " --grid_size=6";
        if (std::string(integrator) == "symplectic_euler") args << " --dt=1e-4";
        const Outcome o = RunIpstep(args.str());
        EXPECT_EQ(o.exit_code, 0) << args.str() << "\n" << o.output;
        EXPECT_NE(o.output.find("done: 2 steps"), std::string::npos) << args.str() << o.output;
      }
    }
  }
}

}  // namespace
