#pragma once
// Ctrl-C (SIGINT) and SIGTERM for the programs. Installed at the start of main, so that a signal at
// any time ends the run with one line and exit 128 + signal (130, 143), never silently, and with no
// temporary file left (base/temp_file_registry.h).
//
// Much of a program's work cannot poll a flag: loading a scene, building MIP chains and the BVH run
// inside libraries for seconds or minutes. So the handler has two behaviours, chosen by the program
// for each phase (set_interrupt_mode):
// - exit_now (the default): the handler itself writes the line with write(2), unlinks the registered
//   temporaries and calls _exit — all async-signal-safe. Nothing half-done is kept: there is no
//   output yet, or the output is temporaries.
// - stop_once: the first signal only sets a flag (interrupt_requested) that the work polls — the
//   renderer checks it between samples and writes what accumulated; a second signal acts as exit_now,
//   for a user who does not want to wait.
// - record: every signal only sets the flag. For short phases that must finish once begun: writing
//   a render's EXR and PNG as a pair (a second Ctrl-C there must not leave one file new and the other
//   old).
#include <fcntl.h>
#include <signal.h>
#include <unistd.h>

#include <atomic>
#include <cstddef>

#include "base/temp_file_registry.h"

namespace svbrdf {

enum class InterruptMode : int { exit_now, stop_once, record };

namespace interrupt_detail {

inline constinit std::atomic<int> g_mode{static_cast<int>(InterruptMode::exit_now)};
inline constinit std::atomic<int> g_signal{0};  // the first signal received, 0 for none
inline constinit std::atomic<bool> g_requested{false};
inline constinit std::atomic<const char*> g_program{"svbrdf"};
inline constinit std::atomic<const char*> g_note{""};
// A duplicate of stderr taken at installation: code that points descriptor 2 elsewhere for a while
// (to silence a library's own messages) must not swallow the line.
inline constinit std::atomic<int> g_stderr{STDERR_FILENO};

inline void append(char* buf, std::size_t& n, std::size_t cap, const char* s) {
  while (*s && n + 1 < cap) buf[n++] = *s++;
}

inline void handle(int sig) {
  int none = 0;
  const bool first = g_signal.compare_exchange_strong(none, sig);
  const auto mode = static_cast<InterruptMode>(g_mode.load());
  if (mode == InterruptMode::record || (mode == InterruptMode::stop_once && first)) {
    g_requested.store(true);
    return;
  }
  char line[512];
  std::size_t n = 0;
  append(line, n, sizeof line, g_program.load());
  append(line, n, sizeof line, sig == SIGTERM ? ": terminated (SIGTERM)" : ": interrupted (SIGINT)");
  append(line, n, sizeof line, g_note.load());
  line[n++] = '\n';
  [[maybe_unused]] const ssize_t written = ::write(g_stderr.load(), line, n);
  remove_registered_temp_files();
  ::_exit(128 + sig);
}

}  // namespace interrupt_detail

// Installs the handler for SIGINT and SIGTERM in exit_now mode. `program` (a string literal) starts
// the line: "svbrdf-render: interrupted (SIGINT)".
inline void install_interrupt_handlers(const char* program) {
  interrupt_detail::g_program.store(program);
  if (const int fd = ::fcntl(STDERR_FILENO, F_DUPFD_CLOEXEC, 3); fd >= 0) interrupt_detail::g_stderr.store(fd);
  struct sigaction action {};
  action.sa_handler = interrupt_detail::handle;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESTART;
  for (const int sig : {SIGINT, SIGTERM}) {
    // A signal the parent set to be ignored stays ignored (a shell's background job, nohup).
    struct sigaction old {};
    if (sigaction(sig, nullptr, &old) == 0 && old.sa_handler == SIG_IGN) continue;
    sigaction(sig, &action, nullptr);
  }
}

// How the next signal is handled; `note` (a string literal, e.g. "; nothing written") ends the line
// an exit_now handler writes.
inline void set_interrupt_mode(InterruptMode mode, const char* note = "") {
  interrupt_detail::g_note.store(note);
  interrupt_detail::g_mode.store(static_cast<int>(mode));
}

// The flag stop_once and record set: work that polls it stops.
inline const std::atomic<bool>& interrupt_requested() { return interrupt_detail::g_requested; }

// The first signal received (SIGINT, SIGTERM), or 0.
inline int interrupt_signal() { return interrupt_detail::g_signal.load(); }

}  // namespace svbrdf
