// Signals of the ptlab command: the interrupt flag and its handler.
#include "tools/ptlab/interrupts.h"

#include <csignal>

namespace ptlab {

std::atomic<bool> g_interrupted{false};
std::atomic<int> g_signal{0};

void OnInterrupt(int signal) {
  g_signal.store(signal);
  g_interrupted.store(true);
  std::signal(SIGINT, SIG_DFL);
  std::signal(SIGTERM, SIG_DFL);
}

}  // namespace ptlab
