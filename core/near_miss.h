// Suggestions for near misses: "--optimiser" -> "did you mean --optimizer?".
#pragma once

#include <string>
#include <vector>

namespace ipstep {

// Edit distance (insertions, deletions, substitutions and transpositions of
// adjacent characters, each 1) between a and b.
int EditDistance(const std::string& a, const std::string& b);

// The candidate closest to `given` if it is a near miss: at most 1 edit for
// names of up to 4 characters, 2 up to 8, 3 beyond (ties: the first). "" if
// none is that close, or if `given` is itself a candidate.
std::string NearMiss(const std::string& given, const std::vector<std::string>& candidates);

}  // namespace ipstep
