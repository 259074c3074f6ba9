// Runs the OpenMP regions of the libraries ipstep calls (CHOLMOD, directly
// and inside Ceres's SUITE_SPARSE solver) on one thread while in scope.
//
// Debian's CHOLMOD runs parts of its supernodal factorisation in OpenMP
// regions of a fixed 4 threads (CHOLMOD_OMP_NUM_THREADS, compiled in). Those
// regions only copy and assemble supernodes (the BLAS does the arithmetic),
// and on a 2-core machine their fork-join cost was a quarter of the run: the
// 36,300-DOF bar's quasi-static solve (bench/quasi_static_bar) took 5.3 s wall
// with projected_newton (0.9 s of it in the kernel's futex calls) against
// 3.6 s with OpenMP limited to one thread (OMP_THREAD_LIMIT=1 and =2 both gave
// 3.6 s); newton spent 30 % of its run in those calls. So CHOLMOD runs with
// OpenMP's max-active-levels at 0 (every region inactive: one thread), and the
// previous value is restored afterwards. The OpenMP runtime is looked up at
// run time: without one (a CHOLMOD built without OpenMP) this does nothing.
#pragma once

namespace ipstep {

class SerialOpenMp {
 public:
  SerialOpenMp();
  ~SerialOpenMp();
  SerialOpenMp(const SerialOpenMp&) = delete;
  SerialOpenMp& operator=(const SerialOpenMp&) = delete;

 private:
  int previous_ = 0;
  bool active_ = false;
};

}  // namespace ipstep
