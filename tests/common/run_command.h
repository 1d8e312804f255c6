#pragma once
// Running a program from a test as a user runs it, through the shell, with its standard input given
// and its outputs captured. One helper for every module's command-line tests.
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "tests/common/temp_dir.h"

namespace svbrdf::testing {

// Runs a shell command with `input` on stdin and stdout and stderr captured in files under `dir`;
// returns the exit status (−1 when it did not exit normally) and both outputs.
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

inline CommandResult run_command(const std::string& command, const std::filesystem::path& dir,
                                 const std::string& input = "") {
  const auto in = dir / "cmd.in", out = dir / "cmd.out", err = dir / "cmd.err";
  std::ofstream(in, std::ios::binary) << input;
  const int rc =
      std::system((command + " <'" + in.string() + "' >'" + out.string() + "' 2>'" + err.string() + "'").c_str());
  CommandResult r;
  r.status = WIFEXITED(rc) ? WEXITSTATUS(rc) : -1;
  r.out = slurp(out);
  r.err = slurp(err);
  for (const auto& p : {in, out, err}) std::filesystem::remove(p);
  return r;
}

}  // namespace svbrdf::testing
