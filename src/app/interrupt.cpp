// Catching the first SIGINT / SIGTERM of a headless render; see interrupt.h.
#include "app/interrupt.h"

#include <signal.h>

#include <array>
#include <atomic>

namespace lueur {
namespace {

// Written by the handler, read by the render loop between frames: an atomic that is lock-free is safe in a handler.
std::atomic<int> g_caught{0};
static_assert(std::atomic<int>::is_always_lock_free);

constexpr std::array<int, 2> kSignals = {SIGINT, SIGTERM};
std::array<struct sigaction, 2> g_previous{};
std::array<bool, 2> g_installed{};

extern "C" void on_interrupt(int signal_number) {
  int none = 0;
  g_caught.compare_exchange_strong(none, signal_number);
}

}  // namespace

InterruptCatcher::InterruptCatcher() {
  g_caught = 0;
  for (size_t i = 0; i < kSignals.size(); ++i) {
    struct sigaction current {};
    if (::sigaction(kSignals[i], nullptr, &current) != 0 || current.sa_handler == SIG_IGN) continue;
    struct sigaction catching {};
    catching.sa_handler = on_interrupt;
    sigemptyset(&catching.sa_mask);
    // SA_RESETHAND: the handler runs once, then the default action is back, so a second Ctrl-C ends the process.
    // SA_RESTART: the reads and writes under way go on instead of failing with EINTR.
    catching.sa_flags = SA_RESETHAND | SA_RESTART;
    g_installed[i] = ::sigaction(kSignals[i], &catching, &g_previous[i]) == 0;
  }
}

InterruptCatcher::~InterruptCatcher() {
  for (size_t i = 0; i < kSignals.size(); ++i)
    if (g_installed[i]) ::sigaction(kSignals[i], &g_previous[i], nullptr);
  g_installed = {};
}

int InterruptCatcher::caught() const { return g_caught.load(); }

const char* signal_name(int signal_number) {
  switch (signal_number) {
    case SIGINT:
      return "SIGINT";
    case SIGTERM:
      return "SIGTERM";
    default:
      return "a signal";
  }
}

}  // namespace lueur
