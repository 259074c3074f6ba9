// An output file of a run (a CSV, a frame, a .pvd): opened when the run
// starts, its stream checked after every row and when it is closed, so that a
// path that cannot be written is an error before the run and a write that
// fails (a full disk: "No space left on device") stops the run instead of
// losing rows silently.
//   OutputFile file(path, "output: stats");   // throws OutputError (kOpen)
//   file.stream() << row << '\n';
//   file.EndRow();                    // notes a failed write (no throw)
//   file.Flush();                     // throws OutputError (kWrite) if one failed
//   file.Close();                     // flushes, closes, throws like Flush()
#pragma once

#include <fstream>
#include <ios>
#include <stdexcept>
#include <string>

namespace ipstep {

// Why an output failed. `label` names the output as InputError's "where: key"
// does: the library's writers say "output: <the caller's name>" (e.g. "output:
// stats", which the programs print as their flag, apps/flag_names.h), a
// program may say "flag: --output". `path` is the file.
//   kOpen:  "<label>: cannot write '<path>': <reason>" (bad input: a missing
//           folder, no permission; the programs exit with code 2)
//   kWrite: "<label>: write failed on '<path>': <reason>" (the disk, not the
//           input: the programs exit with code 3); without a path (a stream
//           such as stdout) "<label>: write failed: <reason>"
class OutputError : public std::runtime_error {
 public:
  enum class Kind { kOpen, kWrite };
  OutputError(const std::string& label, const std::string& path, Kind kind,
              const std::string& reason);
  const std::string& label() const { return label_; }
  const std::string& path() const { return path_; }
  Kind kind() const { return kind_; }

 private:
  std::string label_, path_;
  Kind kind_;
};

class OutputFile {
 public:
  // Creates (truncates) `path`; throws OutputError (kOpen) with the system's
  // reason if it cannot.
  OutputFile(const std::string& path, const std::string& label,
             std::ios::openmode mode = std::ios::out | std::ios::trunc);
  OutputFile(const OutputFile&) = delete;
  OutputFile& operator=(const OutputFile&) = delete;
  // Closes the file without checking (a run that stopped by an exception).
  ~OutputFile() = default;

  std::ostream& stream() { return out_; }
  // After a row: notes the first failed write with its reason (errno is the
  // write's own only right after it). Never throws: callable from inside a
  // solver's callback.
  void EndRow();
  // Throws OutputError (kWrite) if a write failed so far.
  void Check();
  // Writes the buffered rows out, then Check().
  void Flush();
  // Flushes and closes, then Check(). Further writes are errors.
  void Close();

  const std::string& path() const { return path_; }
  const std::string& label() const { return label_; }

 private:
  std::string path_, label_;
  std::ofstream out_;
  int error_ = 0;  // errno of the first failed write, -1 for a failure without one
};

}  // namespace ipstep
