#pragma once
// The fuzz targets: each reads one input through the code a program runs on a file of that kind and
// returns 0. libFuzzer drives them (one executable each, fuzz/libfuzzer_entry.cpp); svbrdf-fuzz-replay
// runs them on saved inputs (fuzz/replay_main.cpp), which is how the regression inputs are tested.
//
// What every target asserts of an input: the code under test reads it, or refuses it with the
// project's input error (svbrdf::Error of kind bad_input: one line, exit 2). Anything else is a
// finding: another exception (a program would call it an internal error, exit 1) aborts with its
// message here; a crash, a sanitizer report, a hang or a memory blow-up is caught by libFuzzer.
#include <cstddef>
#include <cstdint>

namespace svbrdf::fuzz {

// A .gltf or .glb (told apart by the bytes, as the reader does) through load_gltf: the document, its
// scene, materials, and the decoding of every image.
int gltf_input(const std::uint8_t* data, std::size_t size);
// A MIP file (mip/mip_file.h) through read_mip_file.
int mip_file_input(const std::uint8_t* data, std::size_t size);
// An encoded image (PNG, JPEG, OpenEXR, any format OpenImageIO reads) decoded from memory as a glTF
// image is, then taken from sRGB to linear as a color texture is.
int image_input(const std::uint8_t* data, std::size_t size);
// A scene recipe (scenes/recipe.h) through parse_recipe.
int recipe_input(const std::uint8_t* data, std::size_t size);
// svbrdf-brdf's parameters (fuzz/brdf_params_target.cpp says how the input is cut into them).
int brdf_params_input(const std::uint8_t* data, std::size_t size);

}  // namespace svbrdf::fuzz
