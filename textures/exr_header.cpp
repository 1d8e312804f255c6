#include "textures/exr_header.h"

#include <fstream>
#include <functional>

#include "base/error.h"

namespace svbrdf {
namespace {

constexpr unsigned char kMagic[4] = {0x76, 0x2f, 0x31, 0x01};

// Reads n bytes at an offset of a file of `size` bytes; false when they are not all there.
using ReadAt = std::function<bool(std::uint64_t offset, unsigned char* out, std::size_t n)>;

void walk_headers(std::uint64_t size, const ReadAt& read, const std::string& where) {
  const auto fail = [&](const std::string& what) { throw input_error(where, "corrupt OpenEXR header: " + what); };
  unsigned char version[4];
  if (!read(4, version, 4)) fail("the file ends inside the version field");
  const bool multipart = (version[1] & 0x10) != 0;          // bit 12
  const std::size_t max_name = (version[1] & 0x04) ? 255 : 31;  // bit 10
  std::uint64_t at = 8;
  const auto byte = [&]() {
    unsigned char c;
    if (!read(at, &c, 1)) fail("the file ends inside a header");
    ++at;
    return c;
  };
  const auto text = [&](const char* what) {
    std::string s;
    for (unsigned char c = byte(); c != 0; c = byte()) {
      if (s.size() == max_name) fail(std::string("an attribute's ") + what + " is longer than " + std::to_string(max_name) + " bytes");
      s += char(c);
    }
    return s;
  };
  for (int part = 0;; ++part) {
    unsigned char c = byte();
    if (c == 0 && (part > 0 || !multipart)) return;  // the list of headers ends (or an empty single header)
    for (; c != 0; c = byte()) {
      --at;  // c starts the attribute's name
      const std::string name = text("name");
      (void)text("type name");
      unsigned char le[4];
      if (!read(at, le, 4)) fail("the file ends inside the size of attribute \"" + name + "\"");
      at += 4;
      const std::int32_t stated = std::int32_t(std::uint32_t(le[0]) | std::uint32_t(le[1]) << 8 |
                                               std::uint32_t(le[2]) << 16 | std::uint32_t(le[3]) << 24);
      if (stated < 0 || std::uint64_t(stated) > size - at)
        fail("attribute \"" + name + "\" of part " + std::to_string(part) + " states " + std::to_string(stated) +
             " bytes, but the file has " + std::to_string(size - at) + " after it");
      at += std::uint64_t(stated);
    }
    if (!multipart) return;
  }
}

}  // namespace

bool is_exr(std::span<const std::byte> bytes) {
  if (bytes.size() < 4) return false;
  for (int i = 0; i < 4; ++i)
    if (std::to_integer<unsigned char>(bytes[std::size_t(i)]) != kMagic[i]) return false;
  return true;
}

void check_exr_header(std::span<const std::byte> bytes, const std::string& where) {
  if (!is_exr(bytes)) return;
  walk_headers(bytes.size(), [&](std::uint64_t offset, unsigned char* out, std::size_t n) {
    if (offset > bytes.size() || bytes.size() - offset < n) return false;
    for (std::size_t i = 0; i < n; ++i) out[i] = std::to_integer<unsigned char>(bytes[std::size_t(offset) + i]);
    return true;
  }, where);
}

void check_exr_file_header(const std::filesystem::path& path, const std::string& where) {
  std::error_code ec;
  const std::uintmax_t size = std::filesystem::file_size(path, ec);
  std::ifstream f(path, std::ios::binary);
  unsigned char magic[4];
  if (ec || !f || !f.read(reinterpret_cast<char*>(magic), 4) ||
      !is_exr(std::as_bytes(std::span(magic))))
    return;
  walk_headers(size, [&](std::uint64_t offset, unsigned char* out, std::size_t n) {
    if (offset > size || size - offset < n) return false;
    f.clear();
    f.seekg(std::streamoff(offset));
    return bool(f.read(reinterpret_cast<char*>(out), std::streamsize(n)));
  }, where);
}

}  // namespace svbrdf
