#pragma once
// Arithmetic on sizes and offsets read from files, checked before it is trusted: a glTF byteOffset
// near 2^64 must not wrap a bounds check, and a number stored as a double (JSON has no integers of
// its own) must not reach an int conversion unless it is finite, whole and in range — converting
// 1e20 to int is undefined behaviour in C++.
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>

namespace svbrdf {

// a + b, or nothing when it does not fit in 64 bits.
inline std::optional<std::uint64_t> checked_add(std::uint64_t a, std::uint64_t b) {
  std::uint64_t r;
  if (__builtin_add_overflow(a, b, &r)) return std::nullopt;
  return r;
}

// a · b, or nothing when it does not fit in 64 bits.
inline std::optional<std::uint64_t> checked_mul(std::uint64_t a, std::uint64_t b) {
  std::uint64_t r;
  if (__builtin_mul_overflow(a, b, &r)) return std::nullopt;
  return r;
}

// Whether [offset, offset + length) lies inside [0, size), computed without overflow.
inline bool range_inside(std::uint64_t offset, std::uint64_t length, std::uint64_t size) {
  return offset <= size && length <= size - offset;
}

// x as an int when it is finite, whole and within [lo, hi]; nothing otherwise.
inline std::optional<int> whole_int(double x, int lo = std::numeric_limits<int>::min(),
                                    int hi = std::numeric_limits<int>::max()) {
  if (!std::isfinite(x) || x != std::floor(x) || x < double(lo) || x > double(hi)) return std::nullopt;
  return static_cast<int>(x);
}

// x as an int when it is finite, clamped to [lo, hi]; a NaN gives `nan_value`. For quantities
// computed from floats (MIP levels, pixel coordinates) that must become an index.
inline int clamp_to_int(double x, int lo, int hi, int nan_value) {
  if (std::isnan(x)) return nan_value;
  if (x <= double(lo)) return lo;
  if (x >= double(hi)) return hi;
  return static_cast<int>(x);
}

}  // namespace svbrdf
