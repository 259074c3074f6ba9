// Keeps the memory of repeated large factorisations in the process.
//
// Ceres's sparse Cholesky (CXSparse, and the JᵀJ product before it) allocates
// its factor afresh at every Newton iteration and frees it afterwards. With
// glibc's defaults a freed block of that size goes back to the operating
// system (mmap threshold, heap trimming), so every iteration page-faults the
// same megabytes in again. Measured on the 100 x 100 cloth (`ipstep
// --scene=cloth --grid_size=100 --steps=4 --tolerance=1e-6`): 37,600 page
// faults and 576 ms per step with the defaults, 17,600 and 478 ms per step
// with the thresholds below (docs/benchmarks.md). Both thresholds are needed:
// either one alone made it worse (105,000 and 132,000 page faults).
//
// The ipstep programs call this once at start-up; a program that uses the
// library may call it too. It changes process-wide allocator settings (glibc
// mallopt; a no-op elsewhere) and returns false if they were not accepted.
#pragma once

namespace ipstep {

bool KeepLargeAllocations();

}  // namespace ipstep
