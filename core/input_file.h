// The checks every input file passes before it is opened (scene files,
// mesh files): its path holds no NUL byte (a C call would read only the part
// before it), and it is a regular file, not a directory, a device such as
// /dev/zero or a pipe (reading those never ends or blocks).
#pragma once

#include <filesystem>
#include <string>
#include <system_error>

namespace ipstep {

// Empty when `path` may be opened as an input file; else why not ("is a
// directory", "not a regular file", "the path contains a NUL byte"). A path
// that does not exist passes (opening it reports that).
inline std::string InputFileProblem(const std::string& path) {
  if (path.find('\0') != std::string::npos) return "the path contains a NUL byte";
  namespace fs = std::filesystem;
  std::error_code error;
  const fs::file_status status = fs::status(path, error);
  if (fs::is_directory(status)) return "is a directory";
  if (fs::exists(status) && !fs::is_regular_file(status)) return "not a regular file";
  return "";
}

}  // namespace ipstep
