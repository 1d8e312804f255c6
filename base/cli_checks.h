#pragma once
// Number checks for the programs' options, worded for the user. CLI11 2.1's PositiveNumber and
// NonNegativeNumber say "Value 0 not in range 0.000000 to 17976931348623157…" (the largest double,
// all 309 digits); these say "--spp: must be a positive number, got '0'". For the programs only:
// it needs CLI11's headers, which the module libraries do not use.
#include <CLI/CLI.hpp>

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <string>

namespace svbrdf::cli {

// Accepts a finite number that is > 0 (`strict`) or ≥ 0; the type's own parse follows.
inline CLI::Validator number_check(bool strict) {
  const std::string name = strict ? "POSITIVE" : "NONNEGATIVE";
  return CLI::Validator(
      [strict](std::string& text) -> std::string {
        const std::string want = strict ? "a positive number" : "a non-negative number";
        const char* begin = text.c_str();
        char* end = nullptr;
        errno = 0;
        const double v = std::strtod(begin, &end);
        const bool number = end != begin && *end == '\0' && errno != ERANGE && std::isfinite(v);
        if (number && (strict ? v > 0 : v >= 0)) return {};
        return "must be " + want + ", got '" + text + "'";
      },
      name, name);
}

inline const CLI::Validator positive = number_check(true);
inline const CLI::Validator non_negative = number_check(false);

}  // namespace svbrdf::cli
