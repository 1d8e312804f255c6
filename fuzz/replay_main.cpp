// svbrdf-fuzz-replay TARGET PATH...: runs one fuzz target (fuzz/fuzz_targets.h) on saved inputs, every
// file of a folder in name order, and prints one line per input. Each must be read or refused with
// the input error; any other outcome aborts (a non-zero exit). The default test suite replays the
// regression inputs (fuzz/regressions) this way, under whatever compiler and sanitizers the build has.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string_view>
#include <vector>

#include "fuzz/fuzz_targets.h"

namespace {

using Target = int (*)(const std::uint8_t* data, std::size_t size);

Target target_named(std::string_view name) {
  using namespace svbrdf::fuzz;
  if (name == "gltf") return gltf_input;
  if (name == "mip_file") return mip_file_input;
  if (name == "image") return image_input;
  if (name == "recipe") return recipe_input;
  if (name == "brdf_params") return brdf_params_input;
  return nullptr;
}

}  // namespace

int main(int argc, char** argv) {
  const Target target = argc >= 3 ? target_named(argv[1]) : nullptr;
  if (!target) {
    std::fprintf(stderr, "usage: svbrdf-fuzz-replay gltf|mip_file|image|recipe|brdf_params PATH...\n");
    return 2;
  }
  std::vector<std::filesystem::path> inputs;
  for (int i = 2; i < argc; ++i) {
    const std::filesystem::path p = argv[i];
    if (!std::filesystem::is_directory(p)) {
      inputs.push_back(p);
      continue;
    }
    std::vector<std::filesystem::path> files;
    for (const auto& e : std::filesystem::directory_iterator(p))
      if (e.is_regular_file()) files.push_back(e.path());
    std::sort(files.begin(), files.end());
    inputs.insert(inputs.end(), files.begin(), files.end());
  }
  if (inputs.empty()) {
    std::fprintf(stderr, "svbrdf-fuzz-replay: no inputs\n");
    return 2;
  }
  for (const auto& p : inputs) {
    std::ifstream in(p, std::ios::binary);
    const std::vector<char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (!in.eof() && in.fail()) {
      std::fprintf(stderr, "svbrdf-fuzz-replay: cannot read %s\n", p.c_str());
      return 1;
    }
    std::printf("%s: %s\n", argv[1], p.c_str());
    std::fflush(stdout);
    target(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size());
  }
  std::printf("%zu inputs read or refused with the input error\n", inputs.size());
  return 0;
}
