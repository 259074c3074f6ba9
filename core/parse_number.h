// Strict parsing of a number given as text (flag values, option specs): the
// whole text must be one finite number.
#pragma once

#include <cmath>
#include <exception>
#include <string>

namespace ipstep {

// True, with *value set, if `text` is a finite number and nothing else
// (std::stod syntax; leading white space allowed, trailing characters not).
inline bool ParseFiniteNumber(const std::string& text, double* value) {
  size_t used = 0;
  double number = 0.0;
  try {
    number = std::stod(text, &used);
  } catch (const std::exception&) {
    return false;
  }
  if (used == 0 || used != text.size() || !std::isfinite(number)) return false;
  *value = number;
  return true;
}

}  // namespace ipstep
