// Errors caused by user input (scene files, flags). Programs catch them,
// print the message once and exit with code 2; they never abort.
#pragma once

#include <cstddef>
#include <stdexcept>
#include <string>

namespace ipstep {

// Input echoed in an error message (a key, a value, a token) is cut to about
// this many characters, so that a 10 MB key cannot make a 10 MB error line.
constexpr size_t kMaxEchoedInput = 80;

// `text` if it has at most `max` bytes, else its start and end around "..."
// (`max` bytes in all; UTF-8 sequences are not split).
inline std::string ClipInput(const std::string& text, size_t max = kMaxEchoedInput) {
  if (text.size() <= max || max < 8) return text;
  const auto is_continuation = [&text](size_t i) {
    return i < text.size() && (static_cast<unsigned char>(text[i]) & 0xC0) == 0x80;
  };
  size_t head = (max - 3) / 2;
  size_t tail = text.size() - (max - 3 - head);
  while (head > 0 && is_continuation(head)) --head;
  while (is_continuation(tail)) ++tail;
  return text.substr(0, head) + "..." + text.substr(tail);
}

class InputError : public std::runtime_error {
 public:
  // `where` names the file (or "flag"), `key` the key or flag name (cut with
  // ClipInput).
  InputError(const std::string& where, const std::string& key, const std::string& what)
      : std::runtime_error(where + ": " + ClipInput(key) + ": " + what) {}
  explicit InputError(const std::string& message) : std::runtime_error(message) {}
};

// Exit code used for every input error.
constexpr int kInputErrorExitCode = 2;
// Exit code used when a step fails and --on_failure=stop.
constexpr int kStepFailureExitCode = 3;

}  // namespace ipstep
