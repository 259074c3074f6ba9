#include "apps/run_signals.h"

namespace ipstep {
namespace {

volatile std::sig_atomic_t received_signal = 0;

extern "C" void RecordSignal(int signal) {
  if (received_signal == 0) received_signal = signal;
}

// Installs RecordSignal for `signal` unless it is ignored; `previous` gets the
// disposition to restore.
void Install(int signal, struct sigaction* previous) {
  sigaction(signal, nullptr, previous);
  if (previous->sa_handler == SIG_IGN) return;
  struct sigaction action {};
  action.sa_handler = RecordSignal;
  sigemptyset(&action.sa_mask);
  // One-shot: a second signal takes the default action (the program ends at
  // once). SA_RESTART: a write the signal interrupts goes on (stdio would
  // report it as failed otherwise).
  action.sa_flags = SA_RESETHAND | SA_RESTART;
  sigaction(signal, &action, nullptr);
}

}  // namespace

RunSignals::RunSignals() {
  received_signal = 0;
  Install(SIGINT, &previous_int_);
  Install(SIGTERM, &previous_term_);
}

RunSignals::~RunSignals() {
  sigaction(SIGINT, &previous_int_, nullptr);
  sigaction(SIGTERM, &previous_term_, nullptr);
}

const volatile std::sig_atomic_t* RunSignals::flag() { return &received_signal; }

const char* RunSignals::name() const {
  switch (received()) {
    case SIGINT:
      return "SIGINT";
    case SIGTERM:
      return "SIGTERM";
  }
  return "a signal";
}

}  // namespace ipstep
