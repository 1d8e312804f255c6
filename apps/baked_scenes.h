#pragma once
// Where a program finds the scenes the build bakes (scenes/CMakeLists.txt): beside the program in the
// build tree (<build>/scenes/NAME/...), or, installed, in <prefix>/share/svbrdf/scenes
// (cmake/Install.cmake), the program being in <prefix>/bin.
#include <filesystem>
#include <optional>
#include <system_error>
#include <vector>

namespace svbrdf {

// The folders that may hold the baked scenes, in the order a program looks: the build tree's first.
inline std::vector<std::filesystem::path> baked_scene_folders(const char* argv0) {
  std::error_code ec;
  std::filesystem::path exe = std::filesystem::canonical("/proc/self/exe", ec);
  if (ec) exe = std::filesystem::absolute(argv0);
  const std::filesystem::path dir = exe.parent_path();
  return {dir / "scenes", dir.parent_path() / "share" / "svbrdf" / "scenes"};
}

// `relative` under the first of those folders that has it; nullopt where none has.
inline std::optional<std::filesystem::path> find_baked_scene(const char* argv0, const std::filesystem::path& relative) {
  std::error_code ec;
  for (const std::filesystem::path& folder : baked_scene_folders(argv0))
    if (std::filesystem::exists(folder / relative, ec)) return folder / relative;
  return std::nullopt;
}

}  // namespace svbrdf
