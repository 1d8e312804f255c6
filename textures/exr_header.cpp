#include "textures/exr_header.h"

#include <algorithm>
#include <fstream>
#include <functional>
#include <utility>
#include <vector>

#include "base/error.h"

namespace svbrdf {
namespace {

constexpr unsigned char kMagic[4] = {0x76, 0x2f, 0x31, 0x01};

// Reads n bytes at an offset of a file of `size` bytes; false when they are not all there.
using ReadAt = std::function<bool(std::uint64_t offset, unsigned char* out, std::size_t n)>;

// OpenEXR parses the value of a type it knows by the type, not by the stated size: a fixed-size value
// as its fields, a channel list up to its empty name, a preview as width × height pixels, a string
// vector as the lengths inside it. Where that reading and the stated size disagree, OpenEXR carries on
// from another offset than the header states, reading sizes out of the values. So each such value
// must take exactly its stated size, and the counts inside it must stay within it. Returns why not, or
// nothing. (OpenEXR 3.1, ImfAttribute.cpp's registered types and their readValueFrom.)
std::string value_fits(const std::string& type, std::uint64_t at, std::uint32_t size, std::size_t max_name, const ReadAt& read) {
  static const std::pair<const char*, std::uint32_t> kFixed[] = {
      {"box2i", 16}, {"box2f", 16}, {"chromaticities", 32}, {"compression", 1}, {"deepImageState", 1},
      {"double", 8}, {"envmap", 1}, {"float", 4}, {"int", 4}, {"keycode", 28}, {"lineOrder", 1},
      {"m33f", 36}, {"m33d", 72}, {"m44f", 64}, {"m44d", 128}, {"rational", 8}, {"tiledesc", 9},
      {"timecode", 8}, {"v2i", 8}, {"v2f", 8}, {"v2d", 16}, {"v3i", 12}, {"v3f", 12}, {"v3d", 24}};
  for (const auto& [name, bytes] : kFixed)
    if (type == name) return size == bytes ? "" : "states " + std::to_string(size) + " bytes; the type has " + std::to_string(bytes);
  const auto u32 = [&](std::uint64_t offset, std::uint32_t& v) {
    unsigned char le[4];
    if (!read(offset, le, 4)) return false;
    v = std::uint32_t(le[0]) | std::uint32_t(le[1]) << 8 | std::uint32_t(le[2]) << 16 | std::uint32_t(le[3]) << 24;
    return true;
  };
  const std::uint64_t end = at + size;
  if (type == "chlist") {  // entries: name, 16 bytes of fields; an empty name ends the list
    for (std::uint64_t p = at;;) {
      std::size_t length = 0;
      for (unsigned char c = 1;; ++length) {
        if (p + length >= end || !read(p + length, &c, 1)) return "the channel list runs past its stated size";
        if (c == 0) break;
        if (length == max_name) return "a channel name is longer than " + std::to_string(max_name) + " bytes";
      }
      if (length == 0) return p + 1 == end ? "" : "the channel list ends before its stated size";
      // The fields start with the pixel type: OpenEXR defines 0 (uint), 1 (half) and 2 (float);
      // OpenImageIO aborts on any other instead of refusing the file.
      std::uint32_t pixel_type = 0;
      if (end - (p + length + 1) < 16 || !u32(p + length + 1, pixel_type)) return "the channel list runs past its stated size";
      if (pixel_type > 2) return "a channel's pixel type is " + std::to_string(pixel_type) + "; OpenEXR has 0 (uint), 1 (half) and 2 (float)";
      p += length + 1 + 16;
    }
  }
  if (type == "preview") {  // width, height, then 4 bytes a pixel
    std::uint32_t w = 0, h = 0;
    if (size < 8 || !u32(at, w) || !u32(at + 4, h)) return "too short for a preview's size";
    return 8 + 4 * std::uint64_t(w) * h == size ? "" : "a " + std::to_string(w) + "x" + std::to_string(h) + " preview in " + std::to_string(size) + " bytes";
  }
  if (type == "stringvector") {  // per string: its length, then its bytes
    for (std::uint64_t p = at; p < end;) {
      std::uint32_t n = 0;
      if (end - p < 4 || !u32(p, n)) return "a string's length runs past the stated size";
      if (n > end - p - 4) return "a string of " + std::to_string(n) + " bytes runs past the stated size";
      p += 4 + n;
    }
    return "";
  }
  if (type == "floatvector") return size % 4 == 0 ? "" : "states " + std::to_string(size) + " bytes, not whole floats";
  if (type == "idmanifest") return size >= 4 ? "" : "too short for an ID manifest";  // its sizes, then zlib data
  return "";  // a string, or a type OpenEXR keeps as opaque bytes: read at the stated size
}

// Called for every attribute: its part, name, and its value's offset and stated size.
using Visit = std::function<void(int part, const std::string& name, std::uint64_t at, std::uint32_t size)>;

void walk_headers(std::uint64_t size, const ReadAt& read, const std::string& where, const Visit& visit = {}) {
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
      const std::string type = text("type name");
      unsigned char le[4];
      if (!read(at, le, 4)) fail("the file ends inside the size of attribute \"" + name + "\"");
      at += 4;
      const std::int32_t stated = std::int32_t(std::uint32_t(le[0]) | std::uint32_t(le[1]) << 8 |
                                               std::uint32_t(le[2]) << 16 | std::uint32_t(le[3]) << 24);
      if (stated < 0 || std::uint64_t(stated) > size - at)
        fail("attribute \"" + name + "\" of part " + std::to_string(part) + " states " + std::to_string(stated) +
             " bytes, but the file has " + std::to_string(size - at) + " after it");
      if (const std::string why = value_fits(type, at, std::uint32_t(stated), max_name, read); !why.empty())
        fail("attribute \"" + name + "\" of part " + std::to_string(part) + " (" + type + "): " + why);
      if (visit) visit(part, name, at, std::uint32_t(stated));
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

namespace {
// Walks a file's headers, read in blocks (a header is read a byte at a time); false when the file is
// not OpenEXR or cannot be opened.
bool walk_file_headers(const std::filesystem::path& path, const std::string& where, const Visit& visit) {
  std::error_code ec;
  const std::uintmax_t size = std::filesystem::file_size(path, ec);
  std::ifstream f(path, std::ios::binary);
  unsigned char magic[4];
  if (ec || !f || !f.read(reinterpret_cast<char*>(magic), 4) || !is_exr(std::as_bytes(std::span(magic)))) return false;
  constexpr std::uint64_t kBlock = 1 << 16;
  std::vector<unsigned char> block;
  std::uint64_t block_at = 0;
  walk_headers(size, [&](std::uint64_t offset, unsigned char* out, std::size_t n) {
    if (offset > size || size - offset < n) return false;
    if (offset < block_at || offset + n > block_at + block.size()) {
      block_at = offset;
      block.resize(std::size_t(std::min<std::uint64_t>(std::max<std::uint64_t>(kBlock, n), size - offset)));
      f.clear();
      f.seekg(std::streamoff(offset));
      if (!f.read(reinterpret_cast<char*>(block.data()), std::streamsize(block.size()))) {
        block.clear();
        return false;
      }
    }
    std::copy_n(block.data() + (offset - block_at), n, out);
    return true;
  }, where, visit);
  return true;
}
}  // namespace

void check_exr_file_header(const std::filesystem::path& path, const std::string& where) {
  walk_file_headers(path, where, {});
}

std::vector<ExrAttributeValue> find_exr_attribute(const std::filesystem::path& path, const std::string& name,
                                                  const std::string& where) {
  std::vector<ExrAttributeValue> found;
  const bool exr = walk_file_headers(path, where, [&](int part, const std::string& n, std::uint64_t at, std::uint32_t size) {
    if (found.size() <= std::size_t(part)) found.resize(std::size_t(part) + 1);
    if (n == name) found[std::size_t(part)] = {at, size};
  });
  if (!exr) throw input_error(where, "not an OpenEXR file");
  return found;
}

}  // namespace svbrdf
