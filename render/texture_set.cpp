#include "render/texture_set.h"

namespace svbrdf {

namespace {
bool color_slot_uses(const MaterialDesc& m, int texture) {
  return m.base_color_texture.texture == texture || m.emissive_texture.texture == texture ||
         m.specular_color_texture.texture == texture;
}
}  // namespace

TextureSet::TextureSet(const Scene& scene, const ColorConfig& color) {
  std::vector<char> needs_linear(scene.images.size(), 0);
  for (std::size_t t = 0; t < scene.textures.size(); ++t) {
    const int image = scene.textures[t].image;
    if (image < 0) continue;
    for (const MaterialDesc& m : scene.materials)
      if (color_slot_uses(m, int(t))) needs_linear[std::size_t(image)] = 1;
  }
  linear_images_.resize(scene.images.size());
  for (std::size_t i = 0; i < scene.images.size(); ++i) {
    if (!needs_linear[i]) continue;
    linear_images_[i] = scene.images[i].pixels;
    color.srgb_texture_to_linear(linear_images_[i]);
  }
  textures_.resize(scene.textures.size());
  for (std::size_t t = 0; t < scene.textures.size(); ++t) {
    const TextureDesc& d = scene.textures[t];
    if (d.image < 0) continue;
    Prepared& p = textures_[t];
    p.raw = &scene.images[static_cast<std::size_t>(d.image)].pixels;
    if (needs_linear[static_cast<std::size_t>(d.image)]) p.linear = &linear_images_[static_cast<std::size_t>(d.image)];
    p.sampler = d.sampler;
    p.sampler.filter = FilterMode::nearest;  // level0: the nearest texel at the exact uv
  }
}

}  // namespace svbrdf
