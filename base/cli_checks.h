#pragma once
// The programs' command lines, worded for the user. CLI11 2.1's PositiveNumber and NonNegativeNumber
// say "Value 0 not in range 0.000000 to 17976931348623157…" (the largest double, all 309 digits);
// these say "--spp: must be a positive number, got '0'". A parse error is one line with the program's
// name, as every bad input is (CLI11 prints two without it). For the programs only: it needs CLI11's
// headers, which the module libraries do not use.
#include <CLI/CLI.hpp>

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <string>
#include <thread>

#include "base/message_line.h"

namespace svbrdf::cli {

namespace detail {

// `text` as a finite double, or false.
inline bool finite_number(const std::string& text, double& v) {
  const char* begin = text.c_str();
  char* end = nullptr;
  errno = 0;
  v = std::strtod(begin, &end);
  return end != begin && *end == '\0' && errno != ERANGE && std::isfinite(v);
}

inline std::string number_text(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.9g", v);
  return buf;
}

}  // namespace detail

// Accepts a finite number that is > 0 (`strict`) or ≥ 0; the type's own parse follows.
inline CLI::Validator number_check(bool strict) {
  const std::string name = strict ? "POSITIVE" : "NONNEGATIVE";
  return CLI::Validator(
      [strict](std::string& text) -> std::string {
        const std::string want = strict ? "a positive number" : "a non-negative number";
        double v = 0;
        if (detail::finite_number(text, v) && (strict ? v > 0 : v >= 0)) return {};
        return "must be " + want + ", got '" + text + "'";
      },
      name, name);
}

inline const CLI::Validator positive = number_check(true);
inline const CLI::Validator non_negative = number_check(false);

// A finite number in the interval from `lo` to `hi`, each end open or closed:
// "--footprint-scale: must be a number in (0, 64], got '1e30'".
inline CLI::Validator number_in(double lo, double hi, bool lo_open = false, bool hi_open = false) {
  const std::string range = std::string(lo_open ? "(" : "[") + detail::number_text(lo) + ", " + detail::number_text(hi) +
                            (hi_open ? ")" : "]");
  return CLI::Validator(
      [=](std::string& text) -> std::string {
        double v = 0;
        if (detail::finite_number(text, v) && (lo_open ? v > lo : v >= lo) && (hi_open ? v < hi : v <= hi)) return {};
        return "must be a number in " + range + ", got '" + text + "'";
      },
      range, "NUMBER_IN");
}

// Any finite number: "--exposure: must be a finite number, got 'nan'".
inline const CLI::Validator finite = CLI::Validator(
    [](std::string& text) -> std::string {
      double v = 0;
      if (detail::finite_number(text, v)) return {};
      return "must be a finite number, got '" + text + "'";
    },
    "FINITE", "FINITE");

// A whole number from `lo` to `hi` written as digits (no exponent, no fraction), so that the option's
// integer type can hold it: "--spp: must be a whole number from 1 to 2147483647, got '1e10'".
inline CLI::Validator whole_in(long long lo, long long hi) {
  const std::string range = std::to_string(lo) + " to " + std::to_string(hi);
  return CLI::Validator(
      [=](std::string& text) -> std::string {
        const char* begin = text.c_str();
        char* end = nullptr;
        errno = 0;
        const long long v = std::strtoll(begin, &end, 10);
        if (end != begin && *end == '\0' && errno != ERANGE && v >= lo && v <= hi) return {};
        return "must be a whole number from " + range + ", got '" + text + "'";
      },
      range, "WHOLE_IN");
}

// A whole number from 0 to 2^64 − 1 written as digits: CLI11 2.1 takes "-1" for an unsigned option
// and wraps it to 2^64 − 1. "--seed: must be a whole number from 0 to 18446744073709551615, got '-1'".
inline const CLI::Validator unsigned_whole = CLI::Validator(
    [](std::string& text) -> std::string {
      const char* begin = text.c_str();
      char* end = nullptr;
      errno = 0;
      std::strtoull(begin, &end, 10);
      const bool digits = !text.empty() && text.find_first_not_of("0123456789") == std::string::npos;
      if (digits && *end == '\0' && errno != ERANGE) return {};
      return "must be a whole number from 0 to " + std::to_string(std::numeric_limits<unsigned long long>::max()) + ", got '" +
             text + "'";
    },
    "UINT64", "UNSIGNED_WHOLE");

// The largest --max-texels: 2^40 texels, 16 TiB as RGBA floats, past any machine's memory (the memory
// budget refuses far smaller images); a larger number is a typo, not a plan.
inline constexpr long long kMaxTexelsOption = 1LL << 40;

// What a program does with a CLI::ParseError: --help (and --version) print through CLI11 and exit 0;
// any other error is one line, "PROGRAM: message; see --help", and exit 2.
inline int parse_failure(const CLI::App& app, const CLI::ParseError& e, const char* program) {
  if (e.get_exit_code() == 0) return app.exit(e);
  std::fprintf(stderr, "%s: %s; see --help\n", program, message_line(e.what()).c_str());
  return 2;
}

// `requested` worker threads (0: all cores), at most the threads the machine runs at once: more only
// adds switching. Capped with a warning line rather than refused, since a script may carry a count
// from a larger machine.
inline int capped_threads(int requested, const char* program) {
  const unsigned hardware = std::thread::hardware_concurrency();
  if (hardware == 0 || requested <= static_cast<int>(hardware)) return requested;
  std::fprintf(stderr, "%s: warning: --threads %d is more than the %u this machine runs at once; using %u\n", program,
               requested, hardware, hardware);
  return static_cast<int>(hardware);
}

}  // namespace svbrdf::cli
