#pragma once
// svbrdf-render run as a child process for the out-of-core tests (texture_cache_test.cpp,
// mip_tiles_test.cpp): its exit status, its stderr and its peak resident set; and two images compared
// value for value.
#include <gtest/gtest.h>

#include <sys/resource.h>
#include <sys/wait.h>

#include <filesystem>
#include <string>
#include <vector>

#include "tests/common/run_command.h"
#include "tests/common/spawn.h"
#include "tests/common/test_paths.h"
#include "textures/image.h"

namespace svbrdf::testing {

struct Child {
  int status = -1;  // the exit status; −1: killed by a signal, or not run
  std::string err;
  long peak_kb = 0;  // the child's peak resident set (getrusage's ru_maxrss)
};

// svbrdf-render with `args`, its stderr in dir/stderr.txt, its peak resident set read from wait4's rusage.
inline Child render_child(const std::vector<std::string>& args, const std::filesystem::path& dir) {
  std::vector<std::string> all = {std::string(SVBRDF_BINARY_DIR) + "/svbrdf-render"};
  all.insert(all.end(), args.begin(), args.end());
  const std::filesystem::path err = dir / "stderr.txt";
  const pid_t pid = spawn_program(all, err);
  Child r;
  if (pid < 0) return r;
  int status = 0;
  struct rusage usage {};
  if (::wait4(pid, &status, 0, &usage) != pid) return r;
  r.status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.peak_kb = usage.ru_maxrss;
  r.err = slurp(err);
  return r;
}

inline void expect_same_pixels(const std::filesystem::path& a, const std::filesystem::path& b) {
  const Image x = read_image(a), y = read_image(b);
  ASSERT_EQ(x.width, y.width);
  ASSERT_EQ(x.height, y.height);
  ASSERT_EQ(x.channels, y.channels);
  std::size_t differ = 0;
  for (std::size_t k = 0; k < x.pixels.size(); ++k) differ += x.pixels[k] != y.pixels[k];
  EXPECT_EQ(differ, 0u) << a << " and " << b << " differ in " << differ << " of " << x.pixels.size()
                        << " values";
}

}  // namespace svbrdf::testing
