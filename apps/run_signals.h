// SIGINT and SIGTERM during a run: the handler only sets a flag, which the
// run loop reads between steps (RunOptions::interrupt); the step in progress
// finishes, the program writes and closes its files (complete rows only), says
// "interrupted at step N" and exits with 128 + the signal (130 for SIGINT, 143
// for SIGTERM). A second signal ends the program at once (the handler is
// one-shot). A signal ignored when the program starts (SIG_IGN: nohup, a
// background job of a script) stays ignored.
//   RunSignals signals;                    // before the run loop
//   run_options.interrupt = signals.flag();
//   ... RunTrajectory(sim, run_options) ...
//   if (signals.received() != 0) return signals.exit_code();
#pragma once

#include <csignal>

namespace ipstep {

class RunSignals {
 public:
  // Installs the handlers (and clears the flag); the destructor restores the
  // previous ones. One RunSignals at a time.
  RunSignals();
  ~RunSignals();
  RunSignals(const RunSignals&) = delete;
  RunSignals& operator=(const RunSignals&) = delete;

  // 0, or the number of the first signal received.
  static const volatile std::sig_atomic_t* flag();
  int received() const { return *flag(); }
  // 128 + received().
  int exit_code() const { return 128 + received(); }
  // "SIGINT", "SIGTERM" (received() != 0).
  const char* name() const;

 private:
  struct sigaction previous_int_ {};
  struct sigaction previous_term_ {};
};

}  // namespace ipstep
