// ipstep_tune's shards and its max_position measure (apps/tune_program.cc):
// n shards merged pick what the unsharded search picks (with iterations as
// the cost, the pick does not depend on timing); a missing or duplicated
// shard, a shard of another search and bad shard flags are exit code 2 with
// one line naming the flag and the shard. The recommended command line runs
// as printed: it carries the flags the search's runs had and, on a contact
// scene whose kappa adapts to the step, the kappa every run was pinned to.
// Timings are never checked.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "tests/support/run_program.h"

namespace {

namespace fs = std::filesystem;

using Outcome = ipstep::testing::ProgramOutcome;

// A small search: the oscillator to t = 5 s (50 steps of its 0.1 s).
const std::string kSearch = "--scene=oscillator --target_error=1e-3 --at=5 --tune_cost=iterations";

class TuneProgram : public ipstep::testing::ProgramTest {
 protected:
  // stdout alone (the search's progress goes to stderr).
  Outcome Tune(const std::string& arguments) {
    return ipstep::testing::RunProgram(IPSTEP_TUNE_BINARY, arguments, "2>/dev/null");
  }
  // stdout and stderr.
  Outcome TuneAll(const std::string& arguments) {
    return ipstep::testing::RunProgram(IPSTEP_TUNE_BINARY, arguments);
  }
  void ExpectInputError(const std::string& arguments, const std::string& flag,
                        const std::string& detail) {
    const Outcome o = TuneAll(arguments);
    EXPECT_EQ(o.exit_code, 2) << arguments << "\n" << o.output;
    EXPECT_EQ(o.output.rfind("ipstep_tune: error: flag: " + flag + ": ", 0), 0u)
        << arguments << "\n"
        << o.output;
    EXPECT_NE(o.output.find(detail), std::string::npos) << arguments << "\n" << o.output;
    EXPECT_EQ(std::count(o.output.begin(), o.output.end(), '\n'), 1) << o.output;
  }
  // Runs shards 0 .. n-1 of `search` into dir_/name/shard<i>.csv.
  void RunShards(const std::string& search, int n, const std::string& name) {
    fs::create_directories(dir_ / name);
    for (int i = 0; i < n; ++i) {
      const Outcome o = TuneAll(search + " --shard=" + std::to_string(i) + "/" + std::to_string(n) +
                                " --tune_output=" + Shard(name, i));
      ASSERT_EQ(o.exit_code, 0) << o.output;
      EXPECT_NE(o.output.find("shard " + std::to_string(i) + "/" + std::to_string(n) + ": "),
                std::string::npos)
          << o.output;
      EXPECT_EQ(o.output.find("recommended"), std::string::npos) << o.output;
      // The reference is computed by the first shard and read by the others.
      if (i > 0) {
        EXPECT_NE(o.output.find("reference read from"), std::string::npos) << o.output;
      }
    }
  }
  std::string Shard(const std::string& name, int i) {
    return (dir_ / name / ("shard" + std::to_string(i) + ".csv")).string();
  }
};

// The recommended command line and the front's configurations (not its times).
std::string Choice(const std::string& output) {
  std::string choice;
  std::istringstream lines(output);
  for (std::string line; std::getline(lines, line);) {
    if (line.rfind("| ", 0) == 0 && line.rfind("| configuration", 0) != 0) {
      choice += line.substr(0, line.find(" | ")) + "\n";
    }
    if (line.rfind("  ipstep ", 0) == 0) choice += line + "\n";
  }
  return choice;
}

TEST_F(TuneProgram, MergedShardsPickWhatTheUnshardedSearchPicks) {
  const Outcome whole = Tune(kSearch);
  ASSERT_EQ(whole.exit_code, 0) << whole.output;
  const std::string expected = Choice(whole.output);
  ASSERT_NE(expected.find("  ipstep "), std::string::npos) << whole.output;
  for (int n : {2, 3, 5}) {  // 4 families: 5 shards leave one without a family
    const std::string name = "n" + std::to_string(n);
    RunShards(kSearch, n, name);
    const std::string merged_csv = (dir_ / name / "merged.csv").string();
    const Outcome merged = Tune(kSearch + " --merge='" + (dir_ / name).string() +
                                "/shard*.csv' --tune_output=" + merged_csv);
    ASSERT_EQ(merged.exit_code, 0) << merged.output;
    EXPECT_NE(merged.output.find("merged "), std::string::npos) << merged.output;
    EXPECT_EQ(Choice(merged.output), expected) << n << " shards\n" << merged.output;
    // The merged file has the pick, the timing runs and the default, as an unsharded one.
    std::ifstream in(merged_csv);
    std::stringstream text;
    text << in.rdbuf();
    for (const char* role : {",pick,", ",timing,", ",default,"}) {
      EXPECT_NE(text.str().find(role), std::string::npos) << role;
    }
  }
}

TEST_F(TuneProgram, AMissingOrDuplicatedShardOrAnotherSearchIsRefused) {
  RunShards(kSearch, 2, "s");
  const std::string copy = (dir_ / "s" / "copy_of_shard0.csv").string();
  fs::copy_file(Shard("s", 0), copy);
  ExpectInputError(kSearch + " --merge=" + Shard("s", 0), "--merge", "shard 1/2 is missing");
  ExpectInputError(kSearch + " --merge=" + Shard("s", 0) + "," + Shard("s", 1) + "," + copy,
                   "--merge", "shard 0/2 is in two files");
  ExpectInputError("--scene=oscillator --target_error=2e-3 --at=5 --merge='" +
                       (dir_ / "s").string() + "/shard*.csv'",
                   "--merge", "is from another search");
  ExpectInputError(kSearch + " --merge=" + (dir_ / "none*.csv").string(), "--merge", "");
  // A shard file without rows (a header only), and one of another program
  // (ipstep_bench's header).
  {
    std::ifstream in(Shard("s", 0));
    std::string header;
    std::getline(in, header);
    std::ofstream(dir_ / "empty.csv") << header << "\n";
  }
  ExpectInputError(kSearch + " --merge=" + (dir_ / "empty.csv").string(), "--merge", "no rows");
  std::ofstream(dir_ / "bench.csv") << "id,shard\n0,0/1\n";
  ExpectInputError(kSearch + " --merge=" + (dir_ / "bench.csv").string(), "--merge",
                   "not an ipstep_tune shard file");
}

TEST_F(TuneProgram, ShardFlagsAreChecked) {
  const std::string out = " --tune_output=" + (dir_ / "x.csv").string();
  ExpectInputError(kSearch + " --shard=0/2", "--shard", "--tune_output");
  for (const char* bad : {"2/2", "1", "a/b", "-1/2", "0/0", "1/2x", ""}) {
    ExpectInputError(kSearch + " --shard=" + bad + out, "--shard", "i/N");
  }
  ExpectInputError(kSearch + " --shard=0/2 --merge=x.csv" + out, "--merge", "not both");
  ExpectInputError(kSearch + " --merge=", "--merge", "no files");
  ExpectInputError(kSearch + " --tune_cost=wall", "--tune_cost", "'wall'");
  ExpectInputError(kSearch + " --measure=max", "--measure", "max_position");
  EXPECT_FALSE(fs::exists(dir_ / "x.csv"));
}

// --measure=max_position: the error over the run is at least the one at the
// end, so its pick is at least as fine; both within their target.
TEST_F(TuneProgram, MaxPositionMeasuresTheWholeRun) {
  const std::string csv = (dir_ / "max.csv").string();
  const Outcome o = Tune(kSearch + " --measure=max_position --tune_output=" + csv);
  ASSERT_EQ(o.exit_code, 0) << o.output;
  EXPECT_NE(o.output.find("error target 0.001 m over the run"), std::string::npos) << o.output;
  EXPECT_NE(o.output.find("\n  ipstep "), std::string::npos) << o.output;
  std::ifstream in(csv);
  std::string header;
  std::getline(in, header);
  EXPECT_EQ(header.rfind("integrator,optimizer,adaptive,dt,tolerance,error_tolerance,steps,", 0),
            0u)
      << header;
}

}  // namespace

namespace {

// The first line of `output` that starts with `prefix` ("" if none).
std::string LineStartingWith(const std::string& output, const std::string& prefix) {
  std::istringstream lines(output);
  for (std::string line; std::getline(lines, line);) {
    if (line.rfind(prefix, 0) == 0) return line;
  }
  return "";
}

// The built-in drop (kappa fixed at 1e5) and the same scene without its
// kappa, whose barrier then adapts to each run's step: the search pins it
// for every run and the reference, says so, and the recommended command
// carries it with the flags given (--energy_tolerance); with kappa fixed
// nothing is pinned. Both recommended lines run as printed.
TEST_F(TuneProgram, TheRecommendedCommandCarriesTheFlagsGivenAndAPinnedContactStiffness) {
  std::ifstream drop(std::string(IPSTEP_SOURCE_DIR) + "/problems/drop.json");
  ASSERT_TRUE(drop.good());
  std::ostringstream adaptive;
  for (std::string line; std::getline(drop, line);) {
    if (line.find("\"kappa\"") == std::string::npos) adaptive << line << "\n";
  }
  const std::string scene = (dir_ / "drop_adaptive_kappa.json").string();
  std::ofstream(scene) << adaptive.str();
  const std::string search =
      " --target_error=3e-2 --at=0.5 --tune_integrators=newmark "
      "--tune_optimizers=projected_newton --tune_cost=iterations --energy_tolerance=0.2";
  for (const std::string& name : {std::string("drop"), scene}) {
    const bool pinned = name == scene;
    const Outcome o = Tune("--scene=" + name + search);
    ASSERT_EQ(o.exit_code, 0) << o.output;
    const std::string note = LineStartingWith(o.output, "contact: kappa adapts to the step");
    const std::string command = LineStartingWith(o.output, "  ipstep ");
    ASSERT_FALSE(command.empty()) << o.output;
    EXPECT_NE(command.find(" --energy_tolerance=0.2"), std::string::npos) << command;
    EXPECT_EQ(command.find("--target_error"), std::string::npos) << command;
    EXPECT_EQ(!note.empty(), pinned) << o.output;
    const size_t kappa = command.find(" --contact_kappa=");
    EXPECT_EQ(kappa != std::string::npos, pinned) << command;
    if (pinned && kappa != std::string::npos) {
      // The kappa of the note, to the digits it prints.
      const double value = std::stod(command.substr(kappa + 17));
      EXPECT_GT(value, 0.0);
      char shown[40];
      std::snprintf(shown, sizeof(shown), "kappa = %.6g,", value);
      EXPECT_NE(note.find(shown), std::string::npos) << note << "\n" << command;
    }
    const Outcome run = ipstep::testing::RunProgram(
        IPSTEP_BINARY, command.substr(command.find("--scene=")), "2>/dev/null");
    EXPECT_EQ(run.exit_code, 0) << command << "\n" << run.output;
  }
}

}  // namespace
