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
  // `where` names the file (or "flag", "options", "output"), `key` the key,
  // flag or option (cut with ClipInput); what() is "where: key: what".
  InputError(const std::string& where, const std::string& key, const std::string& what)
      : std::runtime_error(where + ": " + ClipInput(key) + ": " + what),
        where_(where),
        key_(ClipInput(key)),
        detail_(what) {}
  // A message of its own form; where(), key() and detail() are empty.
  explicit InputError(const std::string& message) : std::runtime_error(message) {}

  // The parts of what(), for callers that map them (the programs name a flag
  // for an option: apps/flag_names.h).
  const std::string& where() const { return where_; }
  const std::string& key() const { return key_; }
  const std::string& detail() const { return detail_; }

 private:
  std::string where_, key_, detail_;
};

// Exit code used for every input error.
constexpr int kInputErrorExitCode = 2;
// Exit code used when a step fails and --on_failure=stop.
constexpr int kStepFailureExitCode = 3;

}  // namespace ipstep
