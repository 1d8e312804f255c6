#pragma once
// Starting a program as a child of the test, for tests that signal it while it runs: run_command goes
// through the shell and waits, so the test cannot reach the program's process. posix_spawn, not
// fork: the test process has threads (oneTBB, OpenImageIO), and a forked copy of it may deadlock.
#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

extern char** environ;

namespace svbrdf::testing {

// Starts `args` (args[0] the program's path) with stdin from /dev/null, stdout discarded and stderr
// into `err`; returns its process id, or −1.
inline pid_t spawn_program(const std::vector<std::string>& args, const std::filesystem::path& err) {
  std::vector<char*> argv;
  for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&actions, 1, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_addopen(&actions, 2, err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  pid_t pid = -1;
  const int rc = posix_spawn(&pid, argv[0], &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  return rc == 0 ? pid : -1;
}

// How a spawned program ended.
struct ProgramEnd {
  bool exited = false;     // by exit (or return from main), with `code`
  int code = -1;
  int signal = 0;          // killed by this signal
  bool timed_out = false;  // still running after the wait; it was killed
};

// Waits for `pid` up to `seconds`; a program still running then is killed, so that no test leaves a
// process behind.
inline ProgramEnd wait_program(pid_t pid, double seconds) {
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  ProgramEnd e;
  for (;;) {
    int status = 0;
    const pid_t r = ::waitpid(pid, &status, WNOHANG);
    if (r == pid) {
      e.exited = WIFEXITED(status);
      e.code = e.exited ? WEXITSTATUS(status) : -1;
      e.signal = WIFSIGNALED(status) ? WTERMSIG(status) : 0;
      return e;
    }
    if (r < 0) return e;
    if (std::chrono::steady_clock::now() >= end) {
      ::kill(pid, SIGKILL);
      ::waitpid(pid, &status, 0);
      e.timed_out = true;
      return e;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
}

// Waits until the spawned program `pid` has written a line holding `needle` (and not `unless`, when
// given) to its stderr file `err` (a line it prints on reaching a stage), up to `seconds`. False when it ended first or the time ran out; the
// program is not reaped (waitid with WNOWAIT), so wait_program still reads how it ended. This is how
// a test signals a program at a stage of its run, on a loaded machine as on an idle one, rather than
// sleeping and hoping the stage has come.
inline bool wait_for_output(pid_t pid, const std::filesystem::path& err, const std::string& needle, double seconds,
                            const std::string& unless = "") {
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  for (;;) {
    std::ifstream f(err, std::ios::binary);
    for (std::string line; std::getline(f, line);)
      if (!f.eof() && line.find(needle) != std::string::npos && (unless.empty() || line.find(unless) == std::string::npos))
        return true;
    siginfo_t info{};
    if (::waitid(P_PID, static_cast<id_t>(pid), &info, WEXITED | WNOHANG | WNOWAIT) != 0 || info.si_pid == pid) return false;
    if (std::chrono::steady_clock::now() >= end) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
}

// A process id that is not running: that of a child that has exited and been reaped. (The kernel
// hands ids out in increasing order, so it is not reused for a long while.)
inline pid_t dead_pid() {
  const pid_t pid = spawn_program({"/bin/true"}, "/dev/null");
  int status = 0;
  if (pid > 0) ::waitpid(pid, &status, 0);
  return pid;
}

}  // namespace svbrdf::testing
