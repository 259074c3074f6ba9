// Errors caused by user input (scene files, flags). Programs catch them,
// print the message once and exit with code 2; they never abort.
#pragma once

#include <stdexcept>
#include <string>

namespace ipstep {

class InputError : public std::runtime_error {
 public:
  // `where` names the file (or "flag"), `key` the key or flag name.
  InputError(const std::string& where, const std::string& key, const std::string& what)
      : std::runtime_error(where + ": " + key + ": " + what) {}
  explicit InputError(const std::string& message) : std::runtime_error(message) {}
};

// Exit code used for every input error.
constexpr int kInputErrorExitCode = 2;
// Exit code used when a step fails and --on_failure=stop.
constexpr int kStepFailureExitCode = 3;

}  // namespace ipstep
