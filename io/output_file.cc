#include "io/output_file.h"

#include <cerrno>
#include <cstring>
#include <string>

namespace ipstep {
namespace {

std::string Reason(int error) { return error > 0 ? std::strerror(error) : "the stream failed"; }

std::string Message(const std::string& label, const std::string& path, OutputError::Kind kind,
                    const std::string& reason) {
  // A stream without a path (stdout): "<label>: write failed: ...".
  const std::string file = path.empty() ? "" : " '" + path + "'";
  return label + ": " +
         (kind == OutputError::Kind::kOpen ? "cannot write" + file
                                           : "write failed" + (path.empty() ? "" : " on" + file)) +
         ": " + reason;
}

}  // namespace

OutputError::OutputError(const std::string& label, const std::string& path, Kind kind,
                         const std::string& reason)
    : std::runtime_error(Message(label, path, kind, reason)),
      label_(label),
      path_(path),
      kind_(kind) {}

OutputFile::OutputFile(const std::string& path, const std::string& label, std::ios::openmode mode)
    : path_(path), label_(label) {
  errno = 0;
  out_.open(path, mode | std::ios::out);
  if (!out_) {
    throw OutputError(label_, path_, OutputError::Kind::kOpen, Reason(errno > 0 ? errno : -1));
  }
}

void OutputFile::EndRow() {
  if (error_ == 0 && !out_) error_ = errno > 0 ? errno : -1;
}

void OutputFile::Check() {
  EndRow();
  if (error_ != 0) throw OutputError(label_, path_, OutputError::Kind::kWrite, Reason(error_));
}

void OutputFile::Flush() {
  if (error_ == 0 && out_) {
    errno = 0;
    out_.flush();
  }
  Check();
}

void OutputFile::Close() {
  Flush();
  if (!out_.is_open()) return;
  errno = 0;
  out_.close();  // the last write(2) of the buffer, then close(2)
  Check();
}

}  // namespace ipstep
