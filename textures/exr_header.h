#pragma once
// OpenEXR headers walked before OpenEXR reads them. OpenEXR 3.1 allocates an attribute's value at the
// size the file states (a 32-bit count, up to 2 GiB) before it reads a byte of it, so a file of a few
// kilobytes that states a huge attribute makes a program allocate gigabytes and spend seconds before
// the read fails at the end of the file. Here every attribute's stated size must fit in the bytes the
// file has after it, and the value of a type OpenEXR knows must take exactly that size (OpenEXR reads
// those by their type, so a value of another length moves it to where the header says something else);
// nothing is allocated by what the file states.
//
// The layout (OpenEXR, "OpenEXR File Layout", sections "Magic Number", "Version Field" and "Header"):
// the magic 20000630 and a version field whose bit 12 marks a multi-part file and bit 10 long
// attribute names (up to 255 bytes instead of 31); then per part a header, a sequence of attributes
// (name, type name, both null-terminated; a 4-byte little-endian size; the value) ended by a null
// byte; a multi-part file's headers end with one more null byte.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

namespace svbrdf {

// Whether the bytes start with OpenEXR's magic number.
bool is_exr(std::span<const std::byte> bytes);

// Throws svbrdf::Error naming `where` when a header runs past the end or states an attribute larger
// than the rest of the file. Only the headers are checked; OpenEXR checks their values and the pixels.
void check_exr_header(std::span<const std::byte> bytes, const std::string& where);
// The same for a file, reading only its headers. A file that is not OpenEXR passes (its reader
// refuses it); one that cannot be opened too (the caller's open says why).
void check_exr_file_header(const std::filesystem::path& path, const std::string& where);

// Where attribute `name`'s value lies in each part's header of an OpenEXR file, in part order: its
// offset in the file and its stated size (a part without it: size 0 at offset 0). Throws
// svbrdf::Error naming `where` for a file that is not OpenEXR or whose headers check_exr_file_header
// refuses.
struct ExrAttributeValue {
  std::uint64_t offset = 0;
  std::uint32_t size = 0;
};
std::vector<ExrAttributeValue> find_exr_attribute(const std::filesystem::path& path, const std::string& name,
                                                  const std::string& where);

}  // namespace svbrdf
