// The merge of an ipstep_bench sweep's shards (bench/bench_shards.h).
#include "bench/bench_shards.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include <gflags/gflags.h>

#include "apps/shard_files.h"
#include "core/input_error.h"
#include "io/output_file.h"

// Defined with the other flags in bench/bench_program.cc.
DECLARE_string(merge);
DECLARE_string(output);

namespace ipstep {
namespace bench {

// Merges shard files: every shard i/N of one sweep exactly once, every
// configuration id of the sweep (0 .. configurations - 1) exactly once;
// anything else is an InputError naming the shard or the file.
int Merge() {
  const ShardFiles shards = ReadShardFiles(FLAGS_merge);
  const int id_column = shards.Column("id");
  const int size_column = shards.Column("configurations");
  if (id_column < 0) {
    throw InputError("flag", "--merge", "'" + shards.files.front() + "' has no id column");
  }
  std::map<long, std::pair<std::string, std::string>> rows;  // id -> (line, file)
  long sweep_size = -1;
  const int shard_count = shards.count;
  for (const ShardRow& row : shards.rows) {
    const std::string& file = row.file;
    const std::string& shard = row.shard;
    const long id = std::atol(row.fields[id_column].c_str());
    if (id % shard_count != row.index) {
      throw InputError("flag", "--merge",
                       "'" + file + "': configuration " + std::to_string(id) +
                           " does not belong to shard " + shard);
    }
    if (size_column >= 0) {
      const long size = std::atol(row.fields[size_column].c_str());
      if (sweep_size < 0) sweep_size = size;
      if (size != sweep_size) {
        throw InputError("flag", "--merge",
                         "'" + file + "' is from a sweep of " + std::to_string(size) +
                             " configurations, others of " + std::to_string(sweep_size));
      }
    }
    const auto inserted = rows.emplace(id, std::make_pair(row.line, file));
    if (!inserted.second) {
      throw InputError("flag", "--merge",
                       "configuration " + std::to_string(id) + " (shard " + shard +
                           ") is twice: in '" + inserted.first->second.second + "' and '" + file +
                           "'");
    }
  }
  std::map<std::string, std::string> shard_files = shards.shard_files;
  // Every configuration of the sweep: the ids 0 .. size - 1 (files written
  // before the configurations column: up to the largest id seen).
  const long expected =
      sweep_size >= 0 ? sweep_size : (rows.empty() ? 0 : rows.rbegin()->first + 1);
  for (long id = 0; id < expected; ++id) {
    if (rows.count(id) == 0) {
      const std::string shard =
          std::to_string(id % std::max(1, shard_count)) + "/" + std::to_string(shard_count);
      throw InputError(
          "flag", "--merge",
          "configuration " + std::to_string(id) + " is missing: shard " + shard +
              (shard_files.count(shard) ? " ('" + shard_files[shard] + "') is incomplete"
                                        : " is not among the files"));
    }
  }
  if (!rows.empty() && rows.rbegin()->first >= expected) {
    throw InputError("flag", "--merge",
                     "configuration " + std::to_string(rows.rbegin()->first) +
                         " is beyond the sweep's " + std::to_string(expected));
  }
  const std::unique_ptr<OutputFile> output = OpenOutputCreatingFolder(FLAGS_output, "output");
  output->stream() << shards.header << '\n';
  for (const auto& row : rows) {
    output->stream() << row.second.first << '\n';
    output->EndRow();
  }
  output->Close();
  std::printf("merged %zu rows from %zu files (%zu shards) into %s\n", rows.size(),
              shards.files.size(), shard_files.size(), FLAGS_output.c_str());
  return 0;
}

}  // namespace bench
}  // namespace ipstep
