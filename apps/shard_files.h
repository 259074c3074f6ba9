// The shards of a sharded program run (ipstep_bench's sweep, ipstep_tune's
// search): --shard's i/N, the CSV file each shard writes (one row per run,
// with a `shard` column "i/N") and --merge's reading of those files back.
// What a row means, and which rows a complete set must have, is the
// program's (bench/bench_shards.cc, apps/tune_shards.cc).
#pragma once

#include <map>
#include <memory>
#include <string>
#include <vector>

#include "io/output_file.h"

namespace ipstep {

// --shard's "i/N": index i and count N; an InputError naming --shard unless
// 0 <= i < N.
void ParseShard(const std::string& text, int* index, int* count);

// Opens the output file `path` of flag `flag` ("output", "tune_output") for
// writing, creating its folder; an InputError or an OutputError (kOpen) says
// why not.
std::unique_ptr<OutputFile> OpenOutputCreatingFolder(const std::string& path, const char* flag);

// The rows of shard files, read back.
struct ShardRow {
  std::string line;                 // as written
  std::vector<std::string> fields;  // its fields (io/csv_fields.h)
  std::string file;
  std::string shard;  // "i/N"
  int index = 0;      // i
};
struct ShardFiles {
  std::vector<std::string> files;  // sorted
  std::string header;
  std::vector<std::string> columns;
  std::vector<ShardRow> rows;                      // file by file, in file order
  std::map<std::string, std::string> shard_files;  // "i/N" -> its file
  int count = 0;                                   // N (0: no rows)
  // The index of a column; -1 if there is none.
  int Column(const std::string& name) const;
};

// --merge: the files of `list` (comma-separated files or glob patterns),
// each a CSV file with a header and a `shard` column, read whole. An
// InputError naming --merge and the file or the shard for no files, a file
// that cannot be read, a different header, a row with another number of
// fields or no i/N, shards of different N, and a shard in two files.
ShardFiles ReadShardFiles(const std::string& list);

}  // namespace ipstep
