// Outputs that cannot be written and runs that are interrupted, through the
// built programs: a path that cannot be opened is exit code 2, a write that
// fails (/dev/full: "No space left on device") stops the run with exit code 3,
// each with one line naming the flag and the file; SIGINT / SIGTERM finish the
// step in progress, leave complete files and exit with 130 / 143; Ceres logs
// nothing in a normal run. And OutputFile (io/output_file.h) itself.
#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <thread>
#include <tuple>
#include <vector>

#include <gtest/gtest.h>

#include "io/csv_fields.h"
#include "io/output_file.h"
#include "tests/support/run_program.h"

namespace {

namespace fs = std::filesystem;

using Outcome = ipstep::testing::ProgramOutcome;
using ipstep::CsvFields;
using ipstep::OutputError;
using ipstep::OutputFile;

Outcome RunIpstep(const std::string& arguments) {
  return ipstep::testing::RunProgram(IPSTEP_BINARY, arguments);
}

std::vector<std::string> Lines(const std::string& text) {
  std::vector<std::string> lines;
  std::stringstream stream(text);
  for (std::string line; std::getline(stream, line);) lines.push_back(line);
  return lines;
}

std::string ReadFile(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream buffer;
  buffer << in.rdbuf();
  return buffer.str();
}

// The program's lines that glog or Ceres logged ("E20261202 15:04:05.123 ...",
// "W1202 15:04:05.123 ...", "Terminating: ...").
std::vector<std::string> LoggedLines(const std::string& output) {
  static const std::regex logged(R"(^[IWEF]\d{4,8} \d\d:\d\d|Terminating)");
  std::vector<std::string> found;
  for (const std::string& line : Lines(output)) {
    if (std::regex_search(line, logged)) found.push_back(line);
  }
  return found;
}

class OutputSignals : public ipstep::testing::ProgramTest {};

// ---- OutputFile ----

TEST_F(OutputSignals, OutputFileNamesTheOutputThePathAndTheReason) {
  try {
    OutputFile file((dir_ / "missing" / "a.csv").string(), "output: stats");
    FAIL() << "no error";
  } catch (const OutputError& e) {
    EXPECT_EQ(e.kind(), OutputError::Kind::kOpen);
    EXPECT_EQ(std::string(e.what()), "output: stats: cannot write '" +
                                         (dir_ / "missing" / "a.csv").string() +
                                         "': No such file or directory");
  }
  // A failed write is noted by EndRow (which never throws) and reported by Flush.
  OutputFile full("/dev/full", "output: stats");
  for (int i = 0; i < 10000; ++i) {
    full.stream() << "a row of a CSV file that will not fit, " << i << '\n';
    EXPECT_NO_THROW(full.EndRow());
  }
  try {
    full.Flush();
    FAIL() << "no error";
  } catch (const OutputError& e) {
    EXPECT_EQ(e.kind(), OutputError::Kind::kWrite);
    EXPECT_EQ(e.path(), "/dev/full");
    EXPECT_STREQ(e.what(), "output: stats: write failed on '/dev/full': No space left on device");
  }
  EXPECT_THROW(full.Close(), OutputError);
  // A healthy file: rows out, closed.
  {
    OutputFile good((dir_ / "good.csv").string(), "output: stats");
    good.stream() << "a,b\n1,2\n";
    good.EndRow();
    good.Close();
  }
  EXPECT_EQ(ReadFile(dir_ / "good.csv"), "a,b\n1,2\n");
}

// ---- write errors ----

// Each output flag at /dev/full: the run stops with one line naming the flag
// and the file, exit code 3; nothing is reported as done.
TEST_F(OutputSignals, AFullDiskIsExitCode3NamingTheFlag) {
  for (const char* flag : {"stats", "iterations_log", "positions"}) {
    const Outcome o = RunIpstep(std::string("--scene=cloth --steps=5 --") + flag + "=/dev/full");
    EXPECT_EQ(o.exit_code, 3) << flag << "\n" << o.output;
    EXPECT_NE(o.output.find(std::string("ipstep: error: flag: --") + flag +
                            ": write failed on '/dev/full': No space left on device\n"),
              std::string::npos)
        << o.output;
    EXPECT_EQ(o.output.find("done:"), std::string::npos) << o.output;
  }
  // The stats and the iteration log fail before the first step: their header
  // is written (and flushed) when they are opened.
  for (const char* flag : {"stats", "iterations_log"}) {
    const Outcome o = RunIpstep(std::string("--scene=cloth --steps=5 --") + flag + "=/dev/full");
    EXPECT_EQ(o.output.rfind("ipstep: error: flag: --", 0), 0u) << o.output;
    EXPECT_EQ(Lines(o.output).size(), 1u) << o.output;
  }
}

// Frames: a .pvd or a .vtu that cannot be written (here: links to /dev/full),
// in every --frames_format; a 3D solid's surface file too.
TEST_F(OutputSignals, AFrameThatCannotBeWrittenIsExitCode3) {
  const std::pair<const char*, const char*> cases[] = {
      {"run.pvd", "--scene=drop"},
      {"frame_00000.vtu", "--scene=drop --frames_format=ascii"},
      {"frame_00002.vtu", "--scene=drop --frames_format=raw"},
      {"surface_00002.vtu", "--scene=twisted_bar_3d"}};
  for (const auto& [file, scene] : cases) {
    const fs::path frames = dir_ / (std::string("frames_") + file);
    fs::create_directories(frames);
    fs::create_symlink("/dev/full", frames / file);
    const Outcome o =
        RunIpstep(std::string(scene) + " --steps=4 --frame_every=2 --frames=" + frames.string());
    EXPECT_EQ(o.exit_code, 3) << file << "\n" << o.output;
    EXPECT_NE(o.output.find("ipstep: error: flag: --frames: write failed on '" +
                            (frames / file).string() + "': No space left on device"),
              std::string::npos)
        << o.output;
  }
}

// A program's data on stdout (ipstep's summary, ipstep_compare's table) is an
// output too: a full stdout is exit code 3 with a line on stderr.
TEST_F(OutputSignals, AFullStdoutIsExitCode3) {
  for (const std::string& command :
       {std::string(IPSTEP_BINARY) + " --scene=oscillator --steps=3",
        std::string(IPSTEP_COMPARE_BINARY) +
            " --scene=oscillator --steps=3 --integrators=newmark --optimizers=newton"}) {
    // stderr into the pipe, stdout to /dev/full.
    const Outcome o = ipstep::testing::RunProgram(command, "", "2>&1 >/dev/full");
    EXPECT_EQ(o.exit_code, 3) << command << "\n" << o.output;
    EXPECT_NE(o.output.find(": error: output: stdout: write failed: No space left on device"),
              std::string::npos)
        << command << "\n"
        << o.output;
  }
}

// A path that cannot be opened: exit code 2 before the run, with the reason.
TEST_F(OutputSignals, AMissingFolderIsExitCode2) {
  const std::string missing = (dir_ / "no_such_folder" / "x.csv").string();
  for (const char* flag : {"stats", "iterations_log", "positions"}) {
    const Outcome o = RunIpstep(std::string("--scene=cloth --steps=5 --") + flag + "=" + missing);
    EXPECT_EQ(o.exit_code, 2) << o.output;
    EXPECT_EQ(o.output, std::string("ipstep: error: flag: --") + flag + ": cannot write '" +
                            missing + "': No such file or directory\n");
  }
  const Outcome tune = ipstep::testing::RunProgram(
      IPSTEP_TUNE_BINARY, "--scene=oscillator --target_error=1e-3 --tune_output=" + missing);
  EXPECT_EQ(tune.exit_code, 2) << tune.output;
  EXPECT_EQ(tune.output, "ipstep_tune: error: flag: --tune_output: cannot write '" + missing +
                             "': No such file or directory\n");
#ifdef IPSTEP_BENCH_BINARY
  const Outcome bench =
      ipstep::testing::RunProgram(IPSTEP_BENCH_BINARY, "--scenes=oscillator --output=/dev/full");
  EXPECT_EQ(bench.exit_code, 3) << bench.output;
  EXPECT_NE(bench.output.find("ipstep_bench: error: flag: --output: write failed on '/dev/full': "
                              "No space left on device"),
            std::string::npos)
      << bench.output;
#endif
}

// ---- signals ----

struct Interrupted {
  int exit_code = -1;
  std::string output;  // stdout and stderr
  int rows_before_signal = 0;
};

// Starts ipstep with `arguments` (its stats in `stats`), waits until the stats
// hold `rows` rows, sends `sig` and waits for the program. `ignore` is
// ignored in the program from its start (as under nohup).
Interrupted InterruptRun(const std::vector<std::string>& arguments, const fs::path& stats,
                         const fs::path& output, int rows, int sig, int ignore = 0) {
  Interrupted result;
  const pid_t pid = fork();
  if (pid == 0) {
    const int fd = open(output.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    dup2(fd, 1);
    dup2(fd, 2);
    std::signal(SIGINT, ignore == SIGINT ? SIG_IGN : SIG_DFL);
    std::signal(SIGTERM, ignore == SIGTERM ? SIG_IGN : SIG_DFL);
    std::vector<char*> argv;
    std::string binary = IPSTEP_BINARY;
    argv.push_back(binary.data());
    std::vector<std::string> copies = arguments;
    for (std::string& a : copies) argv.push_back(a.data());
    argv.push_back(nullptr);
    execv(binary.c_str(), argv.data());
    _exit(127);
  }
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
  int status = 0;
  while (std::chrono::steady_clock::now() < deadline) {
    const int lines = static_cast<int>(Lines(ReadFile(stats)).size());
    if (lines > rows) {
      result.rows_before_signal = lines - 1;
      break;
    }
    if (waitpid(pid, &status, WNOHANG) == pid) {
      ADD_FAILURE() << "the run ended before the signal:\n" << ReadFile(output);
      return result;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  kill(pid, sig);
  if (sig == ignore) {
    // Ignored: the run goes on; a SIGTERM then stops it.
    std::this_thread::sleep_for(std::chrono::milliseconds(300));
    EXPECT_EQ(waitpid(pid, &status, WNOHANG), 0) << "the ignored signal stopped the run";
    kill(pid, SIGTERM);
  }
  waitpid(pid, &status, 0);
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  result.output = ReadFile(output);
  return result;
}

// The files of an interrupted run: N complete stats rows, the positions of
// the last finished step, "interrupted at step N".
void ExpectCompleteFiles(const Interrupted& r, const fs::path& stats, const fs::path& positions,
                         int nodes, const char* signal_name) {
  std::smatch match;
  ASSERT_TRUE(std::regex_search(
      r.output, match,
      std::regex(R"(interrupted at step (\d+) \()" + std::string(signal_name) + R"(\)\n)")))
      << r.output;
  const int step = std::stoi(match[1]);
  EXPECT_GE(step, r.rows_before_signal);
  const std::string text = ReadFile(stats);
  ASSERT_FALSE(text.empty());
  EXPECT_EQ(text.back(), '\n');
  const std::vector<std::string> lines = Lines(text);
  ASSERT_EQ(static_cast<int>(lines.size()), step + 1) << text;
  const size_t columns = CsvFields(lines[0]).size();
  for (size_t i = 1; i < lines.size(); ++i) {
    EXPECT_EQ(CsvFields(lines[i]).size(), columns) << "row " << i << ": " << lines[i];
    EXPECT_EQ(CsvFields(lines[i])[0], std::to_string(i));
  }
  const std::vector<std::string> rows = Lines(ReadFile(positions));
  ASSERT_EQ(static_cast<int>(rows.size()), nodes + 1);
  EXPECT_EQ(rows[0], "node,x,y");  // the cloth is 2D
  for (int i = 1; i <= nodes; ++i) {
    const std::vector<std::string> fields = CsvFields(rows[i]);
    ASSERT_EQ(fields.size(), 3u) << rows[i];
    EXPECT_EQ(fields[0], std::to_string(i - 1));
    for (int k = 1; k < 3; ++k) {
      char* end = nullptr;
      const double value = std::strtod(fields[k].c_str(), &end);
      EXPECT_TRUE(*end == '\0' && std::isfinite(value)) << rows[i];
    }
  }
  // The summary still says what was done.
  EXPECT_NE(r.output.find("done: " + std::to_string(step) + " steps"), std::string::npos)
      << r.output;
  EXPECT_TRUE(LoggedLines(r.output).empty()) << r.output;
}

TEST_F(OutputSignals, SigintAndSigtermFinishTheStepAndCloseTheFiles) {
  const int nodes = 400;  // the built-in 20 x 20 cloth
  for (const auto& [sig, name, code] :
       {std::tuple{SIGINT, "SIGINT", 130}, std::tuple{SIGTERM, "SIGTERM", 143}}) {
    const fs::path stats = dir_ / (std::string(name) + "_stats.csv");
    const fs::path positions = dir_ / (std::string(name) + "_positions.csv");
    const fs::path log = dir_ / (std::string(name) + "_iterations.csv");
    const Interrupted r =
        InterruptRun({"--scene=cloth", "--steps=100000", "--stats=" + stats.string(),
                      "--positions=" + positions.string(), "--iterations_log=" + log.string()},
                     stats, dir_ / (std::string(name) + ".out"), 5, sig);
    EXPECT_EQ(r.exit_code, code) << r.output;
    ExpectCompleteFiles(r, stats, positions, nodes, name);
    // The iteration log's rows are complete too, the last one of the last step.
    const std::vector<std::string> iterations = Lines(ReadFile(log));
    ASSERT_GT(iterations.size(), 1u);
    for (const std::string& line : iterations) EXPECT_EQ(CsvFields(line).size(), 7u) << line;
  }
}

// A signal ignored at the start (nohup, a background job) stays ignored.
TEST_F(OutputSignals, AnIgnoredSignalStaysIgnored) {
  const fs::path stats = dir_ / "stats.csv";
  const fs::path positions = dir_ / "positions.csv";
  const Interrupted r =
      InterruptRun({"--scene=cloth", "--steps=100000", "--stats=" + stats.string(),
                    "--positions=" + positions.string()},
                   stats, dir_ / "run.out", 3, SIGINT, SIGINT);
  EXPECT_EQ(r.exit_code, 143) << r.output;
  ExpectCompleteFiles(r, stats, positions, 400, "SIGTERM");
}

// ---- Ceres's log ----

// cloth_sphere at h = 0.5 s: the second step starts from the first's failed
// state, where Ceres's trust region cannot evaluate its first point and logs
// "E... trust_region_minimizer.cc:71] Terminating: Residual and Jacobian
// evaluation failed." (twice, as an ERROR). A normal run shows none of it, only
// ipstep's own lines (printed, not logged); -v=1 brings Ceres's log back.
TEST_F(OutputSignals, CeresLogsNothingInANormalRun) {
  const std::string arguments =
      "--scene=cloth_sphere --steps=2 --dt=0.5 --on_failure=continue --noprogress";
  const Outcome quiet = RunIpstep(arguments);
  EXPECT_EQ(quiet.exit_code, 0) << quiet.output;
  EXPECT_TRUE(LoggedLines(quiet.output).empty()) << quiet.output;
  EXPECT_NE(quiet.output.find("\nstep 2 (t = 1): "), std::string::npos) << quiet.output;
  EXPECT_NE(quiet.output.find("\ndone: 2 steps, 2 failed"), std::string::npos) << quiet.output;
  const Outcome verbose = RunIpstep(arguments + " -v=1");
  bool terminating = false;
  for (const std::string& line : LoggedLines(verbose.output)) {
    terminating =
        terminating || (line[0] == 'E' && line.find("Terminating: ") != std::string::npos);
  }
  EXPECT_TRUE(terminating) << "the scene no longer makes Ceres log an error:\n" << verbose.output;
}

}  // namespace
