#include "core/interrupt.h"

#include <atomic>
#include <csignal>
#include <cstring>
#include <string>

namespace hairfit {

namespace {

// Lock-free, hence safe to store from a signal handler.
std::atomic<int> received{0};
static_assert(std::atomic<int>::is_always_lock_free);

extern "C" void on_signal(int signal) {
  received.store(signal, std::memory_order_relaxed);
  std::signal(signal, SIG_DFL);  // a second signal ends the program at once
}

std::string describe(int signal) {
  const char* name = signal == SIGINT ? "SIGINT" : signal == SIGTERM ? "SIGTERM" : nullptr;
  return name ? std::string("interrupted by ") + name : "interrupted by signal " + std::to_string(signal);
}

}  // namespace

Interrupted::Interrupted(int signal) : std::runtime_error(describe(signal)), signal_(signal) {}

void install_interrupt_handlers() {
  struct sigaction action;
  std::memset(&action, 0, sizeof action);
  action.sa_handler = on_signal;
  sigemptyset(&action.sa_mask);
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
}

int interrupt_signal() { return received.load(std::memory_order_relaxed); }

void throw_if_interrupted() {
  if (const int signal = interrupt_signal()) throw Interrupted(signal);
}

void set_interrupt_signal(int signal) { received.store(signal, std::memory_order_relaxed); }

}  // namespace hairfit
