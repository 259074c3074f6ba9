#include "solver/serial_openmp.h"

#include <dlfcn.h>

namespace ipstep {
namespace {

struct OpenMpLevels {
  void (*set)(int) = nullptr;
  int (*get)() = nullptr;
};

const OpenMpLevels& Levels() {
  static const OpenMpLevels levels = [] {
    OpenMpLevels f;
    f.set = reinterpret_cast<void (*)(int)>(dlsym(RTLD_DEFAULT, "omp_set_max_active_levels"));
    f.get = reinterpret_cast<int (*)()>(dlsym(RTLD_DEFAULT, "omp_get_max_active_levels"));
    if (f.get == nullptr) f.set = nullptr;
    return f;
  }();
  return levels;
}

}  // namespace

SerialOpenMp::SerialOpenMp() {
  const OpenMpLevels& levels = Levels();
  if (levels.set == nullptr) return;
  previous_ = levels.get();
  levels.set(0);
  active_ = true;
}

SerialOpenMp::~SerialOpenMp() {
  if (active_) Levels().set(previous_);
}

}  // namespace ipstep
