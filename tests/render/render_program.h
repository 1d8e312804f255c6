#pragma once
// Running svbrdf-render from the program-contract tests (outputs, interrupts, the command line): as
// a child of the test, so a test can signal it, time it and read how it ended.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <string>
#include <vector>

#include "tests/common/run_command.h"
#include "tests/common/spawn.h"
#include "tests/common/test_paths.h"

namespace svbrdf::test {

inline const std::string kRenderProgram = std::string(SVBRDF_BINARY_DIR) + "/svbrdf-render";

struct RenderRun {
  testing::ProgramEnd end;
  std::string err;
  double seconds = 0;
};

// Runs `args` (args[0] the program) to its end or `limit` seconds; stderr goes to DIR/stderr.txt.
inline RenderRun run_to_end(const std::vector<std::string>& args, const std::filesystem::path& dir, double limit = 60) {
  const std::filesystem::path err = dir / "stderr.txt";
  const auto start = std::chrono::steady_clock::now();
  const pid_t pid = testing::spawn_program(args, err);
  RenderRun r;
  if (pid < 0) return r;
  r.end = testing::wait_program(pid, limit);
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  r.err = testing::slurp(err);
  return r;
}

// svbrdf-render with `args`.
inline RenderRun render(std::vector<std::string> args, const std::filesystem::path& dir, double limit = 60) {
  args.insert(args.begin(), kRenderProgram);
  return run_to_end(args, dir, limit);
}

inline int line_count(const std::string& s) { return static_cast<int>(std::count(s.begin(), s.end(), '\n')); }

// Whether every line of `err` starts with "svbrdf-render: ".
inline bool all_prefixed(const std::string& err) {
  std::size_t at = 0;
  while (at < err.size()) {
    if (err.compare(at, 15, "svbrdf-render: ") != 0) return false;
    const std::size_t nl = err.find('\n', at);
    if (nl == std::string::npos) return false;
    at = nl + 1;
  }
  return true;
}

// The temporaries (".NAME.tmpPID.EXT") in `dir`.
inline std::vector<std::string> temp_files(const std::filesystem::path& dir) {
  std::vector<std::string> found;
  for (const auto& e : std::filesystem::directory_iterator(dir))
    if (e.path().filename().string().find(".tmp") != std::string::npos) found.push_back(e.path().filename().string());
  return found;
}

// What `oiiotool --info -v` says of `path`, stdout and stderr together, run in `dir` ("not found" in
// it: OpenImageIO's tools are not installed).
inline std::string oiiotool_info(const std::filesystem::path& path, const std::filesystem::path& dir) {
  const testing::CommandResult r = testing::run_command("oiiotool --info -v '" + path.string() + "'", dir);
  return r.out + r.err;
}

}  // namespace svbrdf::test
