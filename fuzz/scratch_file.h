#pragma once
// The readers of glTF and MIP files take a path: a fuzz input is written to a file in a folder of the
// process's own (made once under $TMPDIR, removed at exit) and read from there.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>

namespace svbrdf::fuzz {

// Writes the bytes to FOLDER/name (replacing what was there) and returns that path.
std::filesystem::path scratch_file(const std::string& name, const std::uint8_t* data, std::size_t size);

}  // namespace svbrdf::fuzz
