#include "geardyn/interrupt.hpp"

#include <csignal>

namespace geardyn::app {
namespace {

// Lock-free, so storing it is async-signal-safe.
std::atomic<bool> g_cancel{false};
static_assert(std::atomic<bool>::is_always_lock_free);

// The handlers to restore on a second signal (set before the handlers are installed).
void (*volatile g_previous_int)(int) = SIG_DFL;
void (*volatile g_previous_term)(int) = SIG_DFL;

extern "C" void OnInterrupt(int signal_number) {
  g_cancel.store(true);
  // std::signal is async-signal-safe (POSIX): the next signal gets the previous handler.
  std::signal(signal_number, signal_number == SIGINT ? g_previous_int : g_previous_term);
}

void (*Previous(void (*handler)(int)))(int) { return handler == SIG_ERR ? SIG_DFL : handler; }

}  // namespace

const std::atomic<bool>* CancelFlag() { return &g_cancel; }

bool Interrupted() { return g_cancel.load(); }

void RequestInterrupt() { g_cancel.store(true); }

InterruptScope::InterruptScope() {
  g_cancel.store(false);
  previous_int_ = Previous(std::signal(SIGINT, SIG_IGN));
  previous_term_ = Previous(std::signal(SIGTERM, SIG_IGN));
  g_previous_int = previous_int_;
  g_previous_term = previous_term_;
  std::signal(SIGINT, OnInterrupt);
  std::signal(SIGTERM, OnInterrupt);
}

InterruptScope::~InterruptScope() {
  std::signal(SIGINT, previous_int_);
  std::signal(SIGTERM, previous_term_);
}

}  // namespace geardyn::app
