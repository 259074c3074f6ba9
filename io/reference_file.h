// Reference solutions (sim/reference.h) kept in files, so that the processes of
// a sharded run (ipstep_bench's and ipstep_tune's shards, a later run of the
// same build) compute each reference once and read it otherwise. A file is
// named by a hash of its key (a line of text that says what the reference is:
// scene, method, steps, end time, the build's commit, ...) and starts with the
// key, which reading checks; it is written to a temporary name and renamed, so
// a reader never sees half a file.
#pragma once

#include <functional>
#include <string>

#include "sim/reference.h"

namespace ipstep {

// The file for `key` in `directory`: ref_<FNV-1a of the key, 16 hex digits>.txt.
std::string ReferenceFileName(const std::string& directory, const std::string& key);

// Reads `file` if it holds the reference for `key`; false if it does not
// exist, holds another key or cannot be read whole (`out` then undefined).
bool ReadReferenceFile(const std::string& file, const std::string& key, ReferenceSolution* out);

// Writes `reference` to `file` (creating its folder); on any failure (a folder
// that cannot be made, a full disk) no file is left and nothing is thrown:
// the caller has the reference in memory.
void WriteReferenceFile(const std::string& file, const std::string& key,
                        const ReferenceSolution& reference);

// The reference for `key`: read from its file in `directory` if that holds
// it, else compute()'d and written there (`computed`, if not null, says
// which). Processes that ask for one key at once compute it once: the first
// holds an exclusive lock (flock) on ref_<hash>.lock beside the file until it
// has written the file, and the others wait for it, then read the file. The
// lock file stays (empty); a lock that cannot be had (a folder that cannot be
// written, a file system without flock) is not waited for. An empty
// `directory`: compute() alone, no file.
ReferenceSolution CachedReference(const std::string& directory, const std::string& key,
                                  const std::function<ReferenceSolution()>& compute,
                                  bool* computed = nullptr);

}  // namespace ipstep
