#include "apps/shard_files.h"

#include <glob.h>

#include <algorithm>
#include <exception>
#include <filesystem>
#include <fstream>
#include <utility>

#include "apps/command_line.h"
#include "core/input_error.h"
#include "io/csv_fields.h"

namespace ipstep {

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

std::unique_ptr<OutputFile> OpenOutputCreatingFolder(const std::string& path, const char* flag) {
  const std::filesystem::path parent = std::filesystem::path(path).parent_path();
  std::error_code error;
  if (!parent.empty() && !std::filesystem::is_directory(parent, error)) {
    std::filesystem::create_directories(parent, error);
    if (error) {
      throw InputError(
          "flag", std::string("--") + flag,
          "cannot create the folder '" + ClipInput(parent.string()) + "': " + error.message());
    }
  }
  return std::make_unique<OutputFile>(path, std::string("flag: --") + flag);
}

int ShardFiles::Column(const std::string& name) const {
  const auto found = std::find(columns.begin(), columns.end(), name);
  return found == columns.end() ? -1 : static_cast<int>(found - columns.begin());
}

ShardFiles ReadShardFiles(const std::string& list) {
  ShardFiles out;
  std::vector<std::string>& files = out.files;
  for (const std::string& pattern : SplitList(list)) {
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
  int shard_column = -1;
  for (const std::string& file : files) {
    std::error_code error;
    if (!std::filesystem::is_regular_file(file, error)) {
      throw InputError("flag", "--merge", "'" + ClipInput(file) + "' is not a regular file");
    }
    std::ifstream in(file);
    if (!in) throw InputError("flag", "--merge", "cannot read '" + ClipInput(file) + "'");
    std::string line;
    if (!std::getline(in, line)) throw InputError("flag", "--merge", "'" + file + "' is empty");
    if (out.header.empty()) {
      out.header = line;
      out.columns = CsvFields(line);
      shard_column = out.Column("shard");
      if (shard_column < 0) {
        throw InputError("flag", "--merge", "'" + file + "' has no shard column");
      }
    }
    if (line != out.header) {
      throw InputError("flag", "--merge", "'" + file + "' has a different header");
    }
    while (std::getline(in, line)) {
      if (line.empty()) continue;
      ShardRow row;
      row.fields = CsvFields(line);
      if (row.fields.size() != out.columns.size()) {
        throw InputError("flag", "--merge",
                         "'" + file + "': a row has " + std::to_string(row.fields.size()) +
                             " fields, the header " + std::to_string(out.columns.size()));
      }
      row.shard = row.fields[shard_column];
      int count = 0;
      try {
        ParseShard(row.shard, &row.index, &count);
      } catch (const InputError&) {
        throw InputError(
            "flag", "--merge",
            "'" + file + "': a row has no shard i/N but '" + ClipInput(row.shard) + "'");
      }
      if (out.count == 0) out.count = count;
      if (count != out.count) {
        throw InputError("flag", "--merge",
                         "shard " + row.shard + " ('" + file + "') is from a run of " +
                             std::to_string(count) + " shards, others of " +
                             std::to_string(out.count));
      }
      const auto owner = out.shard_files.emplace(row.shard, file).first;
      if (owner->second != file) {
        throw InputError(
            "flag", "--merge",
            "shard " + row.shard + " is in two files: '" + owner->second + "' and '" + file + "'");
      }
      row.line = std::move(line);
      row.file = file;
      out.rows.push_back(std::move(row));
    }
  }
  return out;
}

}  // namespace ipstep
