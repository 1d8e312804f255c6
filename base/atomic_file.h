#pragma once
// Output files are written to a temporary name beside the target and renamed into place, so an
// interrupted or failed run never leaves a half-written file (DESIGN.md, "Conventions").
#include <filesystem>
#include <functional>
#include <string>
#include <system_error>
#include <unistd.h>

#include "base/error.h"

namespace svbrdf {

// Calls write(temporary_path) and renames the temporary onto `path` when it returns; removes the
// temporary when it throws. The temporary keeps the target's extension, so writers that choose a
// format by extension (OpenImageIO) see the right one.
inline void write_atomically(const std::filesystem::path& path,
                             const std::function<void(const std::filesystem::path&)>& write) {
  namespace fs = std::filesystem;
  const fs::path dir = path.has_parent_path() ? path.parent_path() : fs::path(".");
  // Appended piece by piece: GCC 12 warns falsely (-Wrestrict, PR 105651) on "." + std::string.
  std::string name = ".";
  name += path.stem().string();
  name += ".tmp";
  name += std::to_string(::getpid());
  name += path.extension().string();
  const fs::path tmp = dir / name;
  try {
    write(tmp);
  } catch (...) {
    std::error_code ec;
    fs::remove(tmp, ec);
    throw;
  }
  std::error_code ec;
  fs::rename(tmp, path, ec);
  if (ec) {
    fs::remove(tmp, ec);
    throw Error(path.string() + ": cannot move the finished file into place: " + ec.message(),
                Error::Kind::bad_input);
  }
}

}  // namespace svbrdf
