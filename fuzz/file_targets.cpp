// The targets whose readers take a file: glTF documents and MIP files.
#include "fuzz/fuzz_targets.h"
#include "fuzz/read_or_refuse.h"
#include "fuzz/scratch_file.h"
#include "gltf/scene_reader.h"
#include "mip/mip_file.h"

namespace svbrdf::fuzz {

int gltf_input(const std::uint8_t* data, std::size_t size) {
  return read_or_refuse("gltf", [&] {
    // One name for both containers: the reader tells a .glb by its magic, not by its name.
    // Camera animations read too: the reader of --frames, beside everything a still render reads.
    LoadOptions options;
    options.camera_animation = true;
    (void)load_gltf(scratch_file("input.gltf", data, size), options);
  });
}

int mip_file_input(const std::uint8_t* data, std::size_t size) {
  return read_or_refuse("mip_file", [&] { (void)read_mip_file(scratch_file("input.exr", data, size)); });
}

}  // namespace svbrdf::fuzz
