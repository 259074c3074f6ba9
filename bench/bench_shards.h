// The merge of an ipstep_bench sweep's shards, for RunBench
// (bench/bench_program.cc; not an interface of its own). --shard's i/N, the
// --output file a shard writes and the reading of shard files back are the
// programs' (apps/shard_files.h).
#pragma once

namespace ipstep {
namespace bench {

// --merge: the shard files (comma-separated files or glob patterns) merged
// into --output, sorted by id; the exit code (0).
int Merge();

}  // namespace bench
}  // namespace ipstep
