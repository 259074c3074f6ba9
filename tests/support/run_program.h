// Test helper: runs a program built by this project and captures its exit code
// and output (stdout and stderr together).
#pragma once

#include <sys/wait.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

namespace ipstep::testing {

struct ProgramOutcome {
  int exit_code = -1;
  std::string output;
};

// `redirect`: the shell redirections of the command ("2>&1 >/dev/full": stdout
// to /dev/full, the outcome's output stderr alone).
inline ProgramOutcome RunProgram(const std::string& binary, const std::string& arguments,
                                 const std::string& redirect = "2>&1") {
  const std::string command = binary + " " + arguments + " " + redirect;
  ProgramOutcome outcome;
  FILE* pipe = popen(command.c_str(), "r");
  if (pipe == nullptr) return outcome;
  char buffer[4096];
  size_t n;
  while ((n = fread(buffer, 1, sizeof(buffer), pipe)) > 0) outcome.output.append(buffer, n);
  const int status = pclose(pipe);
  outcome.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  return outcome;
}

// A fixture with a scratch directory per test (removed afterwards) and the
// ipstep program under test.
class ProgramTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* unit = ::testing::UnitTest::GetInstance();
    dir_ = std::filesystem::temp_directory_path() /
           ("ipstep_" + std::string(unit->current_test_info()->test_suite_name()) + "_" +
            unit->current_test_info()->name() + "_" + std::to_string(unit->random_seed()));
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  // Writes `text` to a file in the scratch directory; returns its path.
  std::string Write(const std::string& name, const std::string& text) {
    const std::filesystem::path path = dir_ / name;
    std::ofstream(path) << text;
    return path.string();
  }

  std::filesystem::path dir_;
};

}  // namespace ipstep::testing
