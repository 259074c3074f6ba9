#include "solver/allocator_tuning.h"

#include <cstdlib>  // defines __GLIBC__ with glibc

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace ipstep {

bool KeepLargeAllocations() {
#if defined(__GLIBC__)
  // The largest mmap threshold glibc accepts on 64-bit systems (32 MiB; fixing
  // it also stops its dynamic adjustment), and no trimming below 1 GiB of free
  // heap.
  const bool mmap_ok = mallopt(M_MMAP_THRESHOLD, 32 * 1024 * 1024) == 1;
  const bool trim_ok = mallopt(M_TRIM_THRESHOLD, 1024 * 1024 * 1024) == 1;
  return mmap_ok && trim_ok;
#else
  return false;
#endif
}

}  // namespace ipstep
