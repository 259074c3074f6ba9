// The shards of an ipstep_bench sweep, for RunBench (bench/bench_program.cc;
// not an interface of its own): --shard's i/N, the --output file a shard or
// the merge writes, and --merge of the shards' CSV files into --output.
#pragma once

#include <memory>
#include <string>

#include "io/output_file.h"

namespace ipstep {
namespace bench {

// --shard's "i/N": index i and count N; an InputError unless 0 <= i < N.
void ParseShard(const std::string& text, int* index, int* count);
// Opens --output for writing, creating its folder.
std::unique_ptr<OutputFile> OpenOutput(const std::string& path);
// --merge: the shard files (comma-separated files or glob patterns) merged
// into --output, sorted by id; the exit code (0).
int Merge();

}  // namespace bench
}  // namespace ipstep
