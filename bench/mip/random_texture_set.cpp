// A seed of the random material family (textures/random_material.h) written as a glTF texture set, as
// `svbrdf-bake material` writes a preset's: DIR/random-SEED_base_color.png (8-bit sRGB),
// _metallic_roughness.png (8-bit), _normal.png (16-bit) and DIR/random-SEED.gltf. The files carry the
// three core maps only: a seed's sheen, if it drew one, is left out. For the cold-build and decoding
// figures on a material no one named (bench/mip/cold_build.sh).
//   random_texture_set SEED SIZE DIR      (prints what the seed drew)
#include <cstdint>
#include <cstdio>
#include <exception>
#include <string>

#include "base/error.h"
#include "scenes/texture_set.h"
#include "textures/material_family.h"
#include "textures/random_material.h"

int main(int argc, char** argv) {
  using namespace svbrdf;
  try {
    if (argc != 4) throw input_error("", "usage: random_texture_set SEED SIZE DIR");
    const std::uint64_t seed = std::stoull(argv[1]);
    const int size = std::stoi(argv[2]);
    if (size < 1 || size > kMaxMaterialSize || (size & (size - 1)) != 0)
      throw input_error(argv[2], "SIZE must be a power of two in [1, " + std::to_string(kMaxMaterialSize) + "]");
    const RandomMaterialDraw draw = draw_random_material(seed);
    ProceduralMaterial m;
    m.preset = "random-" + std::to_string(seed);
    m.seed = seed;
    m.mm_per_texel = 0.1;  // the quad's size only; the family's features are in texels
    store_material_images(random_material_texels(draw, size), ColorConfig::builtin(), m);
    write_texture_set(m, argv[3]);
    std::printf("%s\n", draw.summary().c_str());
    return 0;
  } catch (const Error& e) {
    std::fprintf(stderr, "random_texture_set: %s\n", e.what());
    return e.exit_code();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "random_texture_set: %s\n", e.what());
    return 2;
  }
}
