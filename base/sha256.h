#pragma once
// SHA-256 (FIPS 180-4, "Secure Hash Standard", §6.2): the content address of what a MIP build is
// made from (render/mip_cache.h). A 256-bit digest from a standard, collision-resistant function:
// a key names an entry by what went into it, so two different inputs must not share one.
// Incremental: update() any number of times, then digest() once.
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>

namespace svbrdf {

using Sha256Digest = std::array<std::uint8_t, 32>;

class Sha256 {
 public:
  Sha256();
  void update(std::span<const std::byte> bytes);
  void update(std::string_view text) { update(std::as_bytes(std::span(text.data(), text.size()))); }
  // The digest of everything given so far; the object is spent afterwards.
  Sha256Digest digest();

 private:
  void compress(const std::uint8_t* block);
  std::array<std::uint32_t, 8> h_;
  std::array<std::uint8_t, 64> block_{};
  std::size_t used_ = 0;      // bytes in block_
  std::uint64_t length_ = 0;  // bytes given in all
};

// The digest as 64 lowercase hexadecimal digits.
std::string to_hex(const Sha256Digest& digest);

// One-shot helpers.
Sha256Digest sha256(std::span<const std::byte> bytes);
inline Sha256Digest sha256(std::string_view text) { return sha256(std::as_bytes(std::span(text.data(), text.size()))); }

}  // namespace svbrdf
