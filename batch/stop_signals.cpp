#include "batch/stop_signals.hpp"

#include <unistd.h>

#include <csignal>
#include <algorithm>
#include <cstring>

namespace ddafit::batch {
namespace {

volatile std::sig_atomic_t g_signal = 0;
// The exit message is copied here before the handlers are installed: a handler may only
// call async-signal-safe functions (write, _exit), never allocate.
char g_message[1024] = {0};
size_t g_message_length = 0;

extern "C" void note_signal(int signal) { g_signal = signal; }

extern "C" void exit_on_signal(int signal) {
  const char newline = '\n';
  [[maybe_unused]] ssize_t ignored = write(STDERR_FILENO, &newline, 1);
  ignored = write(STDERR_FILENO, g_message, g_message_length);
  _exit(128 + signal);
}

void install(void (*handler)(int)) {
  struct sigaction action {};
  action.sa_handler = handler;
  sigemptyset(&action.sa_mask);
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
}

}  // namespace

void note_stop_signals() { install(note_signal); }

int stop_signal() { return g_signal; }

void exit_on_stop_signals(const std::string& message) {
  g_message_length = std::min(message.size(), sizeof g_message - 1);
  std::memcpy(g_message, message.data(), g_message_length);
  install(exit_on_signal);
}

int exit_code_for(int signal) { return 128 + signal; }

}  // namespace ddafit::batch
