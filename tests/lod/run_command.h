#pragma once
// Running a program from a test with its outputs captured.
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "tests/common/temp_dir.h"

namespace svbrdf::testing {

// Runs a shell command with stdout and stderr captured in files under `dir`; returns the exit status
// (−1 when it did not exit normally) and both outputs.
struct CommandResult {
  int status = -1;
  std::string out, err;
};

inline std::string slurp(const std::filesystem::path& p) {
  std::ifstream f(p, std::ios::binary);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

inline CommandResult run_command(const std::string& command, const std::filesystem::path& dir) {
  const auto out = dir / "cmd.out", err = dir / "cmd.err";
  const int rc = std::system((command + " >'" + out.string() + "' 2>'" + err.string() + "'").c_str());
  CommandResult r;
  r.status = WIFEXITED(rc) ? WEXITSTATUS(rc) : -1;
  r.out = slurp(out);
  r.err = slurp(err);
  std::filesystem::remove(out);
  std::filesystem::remove(err);
  return r;
}

}  // namespace svbrdf::testing
