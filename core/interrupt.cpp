#include "core/interrupt.hpp"

#include <csignal>

namespace clatter {
namespace {
volatile std::sig_atomic_t g_signal = 0;

extern "C" void on_signal(int signo) { g_signal = signo; }
}  // namespace

void install_interrupt_handlers() {
  struct sigaction action {};
  action.sa_handler = on_signal;
  sigemptyset(&action.sa_mask);
  // Slurm may send SIGTERM more than once (time limit, scancel); its SIGKILL follows after KillWait
  // anyway. A second Ctrl-C, though, means "now".
  sigaction(SIGTERM, &action, nullptr);
  action.sa_flags = SA_RESETHAND;
  sigaction(SIGINT, &action, nullptr);
}

bool interrupt_requested() noexcept { return g_signal != 0; }
int interrupt_signal() noexcept { return g_signal; }

}  // namespace clatter
