// Signals of the ptlab command: SIGINT and SIGTERM stop a render (or converge) after the pass
// in flight; BlockInterrupts holds them while the outputs are written.
#pragma once

#include <pthread.h>
#include <signal.h>

#include <atomic>

namespace ptlab {

/// Set by OnInterrupt: the render (or converge run) stops after the pass in flight.
extern std::atomic<bool> g_interrupted;
/// The signal OnInterrupt received last (SIGINT or SIGTERM; 0 if none).
extern std::atomic<int> g_signal;

// SIGINT (Ctrl-C) and SIGTERM (kill, timeout, schedulers) stop the render after the pass in
// flight; a second one ends the process at once (but not while the outputs are written).
void OnInterrupt(int signal);

// Holds SIGINT and SIGTERM while it lives, so the EXR and the PNG are both written or neither
// is; a signal that arrived meanwhile is delivered when it ends.
class BlockInterrupts {
 public:
  BlockInterrupts() {
    sigset_t set;
    sigemptyset(&set);
    sigaddset(&set, SIGINT);
    sigaddset(&set, SIGTERM);
    pthread_sigmask(SIG_BLOCK, &set, &old_);
  }
  ~BlockInterrupts() { pthread_sigmask(SIG_SETMASK, &old_, nullptr); }

 private:
  sigset_t old_;
};

}  // namespace ptlab
