#include "io/reference_file.h"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <istream>
#include <string>

namespace ipstep {
namespace {

// A number as written (also "nan" and "inf", which operator>> does not read).
bool ReadNumber(std::istream& in, double* value) {
  std::string token;
  if (!(in >> token)) return false;
  char* end = nullptr;
  *value = std::strtod(token.c_str(), &end);
  return end == token.c_str() + token.size();
}

}  // namespace

std::string ReferenceFileName(const std::string& directory, const std::string& key) {
  uint64_t hash = 1469598103934665603ull;
  for (unsigned char c : key) hash = (hash ^ c) * 1099511628211ull;
  char name[40];
  std::snprintf(name, sizeof(name), "ref_%016llx.txt", static_cast<unsigned long long>(hash));
  return (std::filesystem::path(directory) / name).string();
}

// The file: the key; "ok exact dt error steps failed_steps size"; the
// description; x (size numbers); then, if the reference has checkpoints,
// "checkpoints K checkpoint_error" and K times each followed by its size
// positions (a file without that part has none).
bool ReadReferenceFile(const std::string& file, const std::string& key, ReferenceSolution* out) {
  std::ifstream in(file);
  std::string line;
  if (!in || !std::getline(in, line) || line != key) return false;
  int ok = 0, exact = 0;
  long size = 0;
  if (!(in >> ok >> exact) || !ReadNumber(in, &out->dt) || !ReadNumber(in, &out->error) ||
      !(in >> out->steps >> out->failed_steps >> size) || size < 0) {
    return false;
  }
  std::getline(in, line);  // end of the numbers' line
  if (!std::getline(in, out->description)) return false;
  out->ok = ok != 0;
  out->exact = exact != 0;
  out->x.resize(size);
  for (long i = 0; i < size; ++i) {
    if (!ReadNumber(in, &out->x[i])) return false;
  }
  out->checkpoint_times.clear();
  out->checkpoint_x.clear();
  out->checkpoint_error = 0.0;
  std::string word;
  if (!(in >> word)) return in.eof();
  long count = 0;
  if (word != "checkpoints" || !(in >> count) || count < 0 ||
      !ReadNumber(in, &out->checkpoint_error)) {
    return false;
  }
  for (long j = 0; j < count; ++j) {
    double t = 0.0;
    if (!ReadNumber(in, &t)) return false;
    out->checkpoint_times.push_back(t);
    out->checkpoint_x.emplace_back(size);
    for (long i = 0; i < size; ++i) {
      if (!ReadNumber(in, &out->checkpoint_x.back()[i])) return false;
    }
  }
  return true;
}

void WriteReferenceFile(const std::string& file, const std::string& key,
                        const ReferenceSolution& reference) {
  std::error_code error;
  std::filesystem::create_directories(std::filesystem::path(file).parent_path(), error);
  const std::string temporary = file + ".tmp" + std::to_string(::getpid());
  {
    std::ofstream out(temporary);
    if (!out) return;  // no file: the caller has the reference in memory
    out << key << '\n'
        << (reference.ok ? 1 : 0) << ' ' << (reference.exact ? 1 : 0) << ' '
        << std::setprecision(17) << reference.dt << ' ' << reference.error << ' ' << reference.steps
        << ' ' << reference.failed_steps << ' ' << reference.x.size() << '\n'
        << reference.description << '\n';
    for (Eigen::Index i = 0; i < reference.x.size(); ++i) out << reference.x[i] << '\n';
    if (!reference.checkpoint_times.empty()) {
      out << "checkpoints " << reference.checkpoint_times.size() << ' '
          << reference.checkpoint_error << '\n';
      for (size_t j = 0; j < reference.checkpoint_times.size(); ++j) {
        out << reference.checkpoint_times[j] << '\n';
        for (Eigen::Index i = 0; i < reference.x.size(); ++i) {
          out << reference.checkpoint_x[j][i] << '\n';
        }
      }
    }
    out.close();
    if (!out) {  // e.g. a full disk: no file rather than a truncated one
      std::filesystem::remove(temporary, error);
      return;
    }
  }
  std::filesystem::rename(temporary, file, error);
  if (error) std::filesystem::remove(temporary, error);
}

ReferenceSolution CachedReference(const std::string& directory, const std::string& key,
                                  const std::function<ReferenceSolution()>& compute,
                                  bool* computed) {
  if (computed != nullptr) *computed = false;
  ReferenceSolution reference;
  const std::string file = directory.empty() ? "" : ReferenceFileName(directory, key);
  if (!file.empty() && ReadReferenceFile(file, key, &reference)) return reference;
  int lock = -1;
  if (!file.empty()) {
    std::error_code error;
    std::filesystem::create_directories(directory, error);
    const std::string lock_file = file.substr(0, file.size() - 4) + ".lock";  // not ".txt"
    lock = ::open(lock_file.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (lock >= 0 && ::flock(lock, LOCK_EX) != 0) {
      ::close(lock);
      lock = -1;
    }
    // Another process may have written it while this one waited.
    if (lock >= 0 && ReadReferenceFile(file, key, &reference)) {
      ::close(lock);  // releases the lock
      return reference;
    }
  }
  if (computed != nullptr) *computed = true;
  try {
    reference = compute();
  } catch (...) {
    if (lock >= 0) ::close(lock);
    throw;
  }
  if (!file.empty()) WriteReferenceFile(file, key, reference);
  if (lock >= 0) ::close(lock);
  return reference;
}

}  // namespace ipstep
