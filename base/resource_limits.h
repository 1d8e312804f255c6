#pragma once
// What one input may make a program allocate. A file states its own sizes (an accessor's count, an
// image's width, a MIP level's texels, --res); those are checked against these limits before any
// allocation, so a few hundred hostile bytes are refused with one line instead of exhausting the
// machine's memory or running for minutes.
//
// - memory_bytes: the largest single allocation an input may ask for. By default half the machine's
//   physical memory: the program's other data (the scene, its MIP chains, the frame) must fit
//   beside it, and a request past it would make the machine swap or the allocator fail.
// - max_texels: the most texels one image (a texture, a MIP level 0, a frame) may have. By default
//   8192² = 2^26, the largest size texture authoring tools export as standard; `--max-texels`
//   raises it. One such RGBA float image is 1 GiB as decoded.
#include <cstdint>
#include <string>
#include <unistd.h>

#include "base/checked_number.h"
#include "base/error.h"

namespace svbrdf {

struct ResourceLimits {
  std::uint64_t memory_bytes = 0;
  std::uint64_t max_texels = std::uint64_t(1) << 26;
};

inline std::uint64_t physical_memory_bytes() {
  const long pages = ::sysconf(_SC_PHYS_PAGES);
  const long page = ::sysconf(_SC_PAGESIZE);
  if (pages <= 0 || page <= 0) return std::uint64_t(8) << 30;  // unknown: assume a small machine
  return std::uint64_t(pages) * std::uint64_t(page);
}

// The process's limits; the programs set them from their options before reading input.
inline ResourceLimits& resource_limits() {
  static ResourceLimits limits{physical_memory_bytes() / 2, std::uint64_t(1) << 26};
  return limits;
}

inline std::string byte_size_text(std::uint64_t bytes) {
  const double gib = double(bytes) / double(std::uint64_t(1) << 30);
  if (gib >= 1) return std::to_string(static_cast<std::uint64_t>(gib * 10 + 0.5) / 10) + "." +
                           std::to_string(static_cast<std::uint64_t>(gib * 10 + 0.5) % 10) + " GiB";
  return std::to_string(bytes / 1024 + (bytes % 1024 != 0)) + " KiB";
}

// The largest encoded image file that can hold --max-texels texels: 16 bytes a texel (four float
// channels stored uncompressed, as an EXR may be) plus 16 MiB for headers and metadata. A larger
// image file cannot be one the programs would decode, so it is refused before it is read.
inline std::uint64_t image_file_limit() {
  const auto bytes = checked_mul(resource_limits().max_texels, 16);
  const std::uint64_t cap = std::uint64_t(1) << 62;
  return (bytes && *bytes < cap ? *bytes : cap) + (std::uint64_t(16) << 20);
}

// Throws input_error(where, ...) unless `count` elements of `element_bytes` each fit the memory
// budget; `what` names them ("positions", "texels").
inline void check_allocation(std::uint64_t count, std::uint64_t element_bytes, const std::string& where,
                             const std::string& what) {
  const auto bytes = checked_mul(count, element_bytes);
  const std::uint64_t budget = resource_limits().memory_bytes;
  if (!bytes || *bytes > budget)
    throw input_error(where, std::to_string(count) + " " + what + " would need " +
                                 (bytes ? byte_size_text(*bytes) : std::string("more than 2^64 bytes")) +
                                 ", over the memory budget of " + byte_size_text(budget) +
                                 " (half the machine's memory)");
}

// Throws input_error(where, ...) unless a width × height image fits --max-texels and the budget
// at `texel_bytes` each.
inline void check_image_size(std::uint64_t width, std::uint64_t height, std::uint64_t texel_bytes,
                             const std::string& where) {
  const auto texels = checked_mul(width, height);
  const std::uint64_t max = resource_limits().max_texels;
  if (!texels || *texels > max)
    throw input_error(where, std::to_string(width) + "x" + std::to_string(height) + " is beyond the " +
                                 std::to_string(max) + " texels allowed (--max-texels)");
  check_allocation(*texels, texel_bytes, where, "texels");
}

}  // namespace svbrdf
