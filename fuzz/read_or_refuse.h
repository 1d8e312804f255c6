#pragma once
// The contract every fuzz target checks (fuzz/fuzz_targets.h): an input is read or refused with the
// one-line input error; any other outcome aborts, which libFuzzer reports as a crash and saves.
#include <cstdio>
#include <cstdlib>
#include <exception>

#include "base/error.h"
#include "base/message_line.h"
#include "base/resource_limits.h"

namespace svbrdf::fuzz {

// Limits a little below the programs' defaults (base/resource_limits.h), so that an input that asks for
// the most it may is still inside libFuzzer's -rss_limit_mb (2 GiB) and the check that refuses one more
// byte is what gets exercised: 2^20 texels (16 MiB as RGBA floats), one allocation at most 256 MiB.
inline void set_fuzz_limits() {
  static const bool once = [] {
    resource_limits() = ResourceLimits{std::uint64_t(256) << 20, std::uint64_t(1) << 20};
    return true;
  }();
  (void)once;
}

template <class Body>
int read_or_refuse(const char* target, Body&& body) {
  set_fuzz_limits();
  try {
    body();
  } catch (const Error& e) {
    if (e.kind() == Error::Kind::bad_input) return 0;
    std::fprintf(stderr, "%s: not an input error (exit 1 path): %s\n", target, message_line(e.what()).c_str());
    std::abort();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: internal error: %s\n", target, message_line(e.what()).c_str());
    std::abort();
  }
  return 0;
}

}  // namespace svbrdf::fuzz
