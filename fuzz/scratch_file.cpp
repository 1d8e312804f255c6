#include "fuzz/scratch_file.h"

#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <system_error>

namespace svbrdf::fuzz {
namespace {

std::filesystem::path make_folder() {
  const char* tmp = std::getenv("TMPDIR");
  std::string pattern = std::string(tmp && *tmp ? tmp : "/tmp") + "/svbrdf-fuzz-XXXXXX";
  if (!::mkdtemp(pattern.data())) throw std::runtime_error("cannot make a scratch folder under " + pattern);
  return pattern;
}

// Never destroyed, so that the exit handler that removes the folder may still name it.
const std::filesystem::path& folder() {
  static const std::filesystem::path* f = [] {
    const auto* made = new std::filesystem::path(make_folder());
    std::atexit([] {
      std::error_code ec;
      std::filesystem::remove_all(folder(), ec);
    });
    return made;
  }();
  return *f;
}

}  // namespace

std::filesystem::path scratch_file(const std::string& name, const std::uint8_t* data, std::size_t size) {
  const std::filesystem::path path = folder() / name;
  std::FILE* f = std::fopen(path.c_str(), "wb");
  if (!f) throw std::runtime_error("cannot write " + path.string());
  const bool ok = std::fwrite(data, 1, size, f) == size;
  if (std::fclose(f) != 0 || !ok) throw std::runtime_error("cannot write " + path.string());
  return path;
}

}  // namespace svbrdf::fuzz
