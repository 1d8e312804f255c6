// libFuzzer's entry point for one target: built once per target with SVBRDF_FUZZ_TARGET naming its
// function (fuzz/CMakeLists.txt).
#include "fuzz/fuzz_targets.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return svbrdf::fuzz::SVBRDF_FUZZ_TARGET(data, size);
}
