// The shards of an ipstep_bench sweep (bench/bench_shards.h): --shard's i/N,
// the --output file and --merge of the shards' CSV files.
#include "bench/bench_shards.h"

#include <glob.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include <gflags/gflags.h>

#include "apps/command_line.h"
#include "core/input_error.h"
#include "io/csv_fields.h"
#include "io/output_file.h"

// Defined with the other flags in bench/bench_program.cc.
DECLARE_string(merge);
DECLARE_string(output);

namespace ipstep {
namespace bench {

void ParseShard(const std::string& text, int* index, int* count) {
  const size_t slash = text.find('/');
  bool ok = slash != std::string::npos;
  if (ok) {
    try {
      size_t a = 0, b = 0;
      *index = std::stoi(text.substr(0, slash), &a);
      *count = std::stoi(text.substr(slash + 1), &b);
      ok = a == slash && b == text.size() - slash - 1 && *count >= 1 && *index >= 0 &&
           *index < *count;
    } catch (const std::exception&) {
      ok = false;
    }
  }
  if (!ok) {
    throw InputError("flag", "--shard",
                     "must be i/N with 0 <= i < N, got '" + ClipInput(text) + "'");
  }
}

// Opens --output for writing, creating its folder; an InputError or an
// OutputError (kOpen) says why not.
std::unique_ptr<OutputFile> OpenOutput(const std::string& path) {
  const std::filesystem::path parent = std::filesystem::path(path).parent_path();
  std::error_code error;
  if (!parent.empty() && !std::filesystem::is_directory(parent, error)) {
    std::filesystem::create_directories(parent, error);
    if (error) {
      throw InputError(
          "flag", "--output",
          "cannot create the folder '" + ClipInput(parent.string()) + "': " + error.message());
    }
  }
  return std::make_unique<OutputFile>(path, "flag: --output");
}

// Merges shard files: every shard i/N of one sweep exactly once, every
// configuration id of the sweep (0 .. configurations - 1) exactly once;
// anything else is an InputError naming the shard or the file.
int Merge() {
  std::vector<std::string> files;
  for (const std::string& pattern : SplitList(FLAGS_merge)) {
    glob_t matches;
    if (glob(pattern.c_str(), 0, nullptr, &matches) == 0) {
      for (size_t i = 0; i < matches.gl_pathc; ++i) files.push_back(matches.gl_pathv[i]);
    } else {
      files.push_back(pattern);  // reported below as unreadable
    }
    globfree(&matches);
  }
  std::sort(files.begin(), files.end());
  files.erase(std::unique(files.begin(), files.end()), files.end());
  if (files.empty()) throw InputError("flag", "--merge", "no files");
  std::string header;
  std::vector<std::string> columns;
  int id_column = -1, shard_column = -1, size_column = -1;
  std::map<long, std::pair<std::string, std::string>> rows;  // id -> (line, file)
  std::map<std::string, std::string> shard_files;            // "i/N" -> file
  long sweep_size = -1;
  int shard_count = 0;
  for (const std::string& file : files) {
    std::error_code error;
    if (!std::filesystem::is_regular_file(file, error)) {
      throw InputError("flag", "--merge", "'" + ClipInput(file) + "' is not a regular file");
    }
    std::ifstream in(file);
    if (!in) throw InputError("flag", "--merge", "cannot read '" + ClipInput(file) + "'");
    std::string line;
    if (!std::getline(in, line)) throw InputError("flag", "--merge", "'" + file + "' is empty");
    if (header.empty()) {
      header = line;
      columns = CsvFields(header);
      for (int c = 0; c < static_cast<int>(columns.size()); ++c) {
        if (columns[c] == "id") id_column = c;
        if (columns[c] == "shard") shard_column = c;
        if (columns[c] == "configurations") size_column = c;
      }
      if (id_column < 0 || shard_column < 0) {
        throw InputError("flag", "--merge", "'" + file + "' has no id or shard column");
      }
    }
    if (line != header) {
      throw InputError("flag", "--merge", "'" + file + "' has a different header");
    }
    while (std::getline(in, line)) {
      if (line.empty()) continue;
      const std::vector<std::string> fields = CsvFields(line);
      if (fields.size() != columns.size()) {
        throw InputError("flag", "--merge",
                         "'" + file + "': a row has " + std::to_string(fields.size()) +
                             " fields, the header " + std::to_string(columns.size()));
      }
      const long id = std::atol(fields[id_column].c_str());
      const std::string& shard = fields[shard_column];
      int index = 0, count = 0;
      try {
        ParseShard(shard, &index, &count);
      } catch (const InputError&) {
        throw InputError("flag", "--merge",
                         "'" + file + "': configuration " + std::to_string(id) +
                             " has no shard i/N but '" + ClipInput(shard) + "'");
      }
      if (shard_count == 0) shard_count = count;
      if (count != shard_count) {
        throw InputError("flag", "--merge",
                         "shard " + shard + " ('" + file + "') is from a sweep of " +
                             std::to_string(count) + " shards, others of " +
                             std::to_string(shard_count));
      }
      const auto owner = shard_files.emplace(shard, file).first;
      if (owner->second != file) {
        throw InputError(
            "flag", "--merge",
            "shard " + shard + " is in two files: '" + owner->second + "' and '" + file + "'");
      }
      if (id % count != index) {
        throw InputError("flag", "--merge",
                         "'" + file + "': configuration " + std::to_string(id) +
                             " does not belong to shard " + shard);
      }
      if (size_column >= 0) {
        const long size = std::atol(fields[size_column].c_str());
        if (sweep_size < 0) sweep_size = size;
        if (size != sweep_size) {
          throw InputError("flag", "--merge",
                           "'" + file + "' is from a sweep of " + std::to_string(size) +
                               " configurations, others of " + std::to_string(sweep_size));
        }
      }
      const auto inserted = rows.emplace(id, std::make_pair(line, file));
      if (!inserted.second) {
        throw InputError("flag", "--merge",
                         "configuration " + std::to_string(id) + " (shard " + shard +
                             ") is twice: in '" + inserted.first->second.second + "' and '" + file +
                             "'");
      }
    }
  }
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
  const std::unique_ptr<OutputFile> output = OpenOutput(FLAGS_output);
  output->stream() << header << '\n';
  for (const auto& row : rows) {
    output->stream() << row.second.first << '\n';
    output->EndRow();
  }
  output->Close();
  std::printf("merged %zu rows from %zu files (%zu shards) into %s\n", rows.size(), files.size(),
              shard_files.size(), FLAGS_output.c_str());
  return 0;
}

}  // namespace bench
}  // namespace ipstep
