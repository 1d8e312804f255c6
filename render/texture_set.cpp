#include "render/texture_set.h"

#include <algorithm>
#include <cmath>

namespace svbrdf {

float srgb_to_linear(float c) {
  return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}

namespace {

int wrap(int i, int n, WrapMode mode) {
  switch (mode) {
    case WrapMode::repeat: {
      const int r = i % n;
      return r < 0 ? r + n : r;
    }
    case WrapMode::clamp_to_edge: return std::clamp(i, 0, n - 1);
    case WrapMode::mirrored_repeat: {
      const int period = 2 * n;
      int r = i % period;
      if (r < 0) r += period;
      return r < n ? r : period - 1 - r;
    }
  }
  return 0;
}

// Texel index along an axis of n texels for coordinate t: texel i covers [i, i+1)/n.
int texel_index(float t, int n, WrapMode mode) {
  float x = t * float(n);
  if (!std::isfinite(x)) return 0;
  // Keep far-away coordinates in int range; repeat/mirror are periodic in 2n, clamp constant outside.
  if (mode == WrapMode::clamp_to_edge) x = std::clamp(x, -1.0f, float(n) + 1.0f);
  else if (std::fabs(x) > float(1 << 24)) x = std::fmod(x, float(2 * n));
  return wrap(static_cast<int>(std::floor(x)), n, mode);
}

glm::vec4 texel(const Image& image, int i, int j) {
  const float* p = image.pixels.data() + (std::size_t(j) * image.width + i) * image.channels;
  switch (image.channels) {
    case 1: return {p[0], p[0], p[0], 1.0f};
    case 2: return {p[0], p[0], p[0], p[1]};
    case 3: return {p[0], p[1], p[2], 1.0f};
    default: return {p[0], p[1], p[2], p[3]};
  }
}

bool color_slot_uses(const MaterialDesc& m, int texture) {
  return m.base_color_texture.texture == texture || m.emissive_texture.texture == texture ||
         m.specular_color_texture.texture == texture;
}

}  // namespace

TextureSet::TextureSet(const Scene& scene) : scene_(scene), images_(scene.images.size()) {
  for (std::size_t i = 0; i < scene.images.size(); ++i) images_[i].raw = &scene.images[i].pixels;
  std::vector<char> needs_linear(scene.images.size(), 0);
  for (std::size_t t = 0; t < scene.textures.size(); ++t) {
    const int image = scene.textures[t].image;
    if (image < 0) continue;
    for (const MaterialDesc& m : scene.materials)
      if (color_slot_uses(m, int(t))) needs_linear[std::size_t(image)] = 1;
  }
  for (std::size_t i = 0; i < scene.images.size(); ++i) {
    if (!needs_linear[i]) continue;
    Image lin = scene.images[i].pixels;
    const int color_channels = lin.channels >= 3 ? 3 : 1;  // gray (+alpha): the gray channel is color
    for (std::size_t p = 0; p < std::size_t(lin.width) * lin.height; ++p)
      for (int c = 0; c < color_channels; ++c) {
        float& v = lin.pixels[p * lin.channels + c];
        v = srgb_to_linear(v);
      }
    images_[i].linear = std::move(lin);
  }
}

glm::vec4 TextureSet::lookup(const TextureRef& ref, glm::vec2 uv, bool color) const {
  const TextureDesc& tex = scene_.textures[static_cast<std::size_t>(ref.texture)];
  const Prepared& p = images_[static_cast<std::size_t>(tex.image)];
  const Image& image = color && !p.linear.pixels.empty() ? p.linear : *p.raw;
  const glm::vec2 st = ref.transform.apply(uv);
  const int i = texel_index(st.x, image.width, tex.sampler.wrap_s);
  const int j = texel_index(st.y, image.height, tex.sampler.wrap_t);
  return texel(image, i, j);
}

glm::ivec2 TextureSet::size(const TextureRef& ref) const {
  const TextureDesc& tex = scene_.textures[static_cast<std::size_t>(ref.texture)];
  const Image& im = *images_[static_cast<std::size_t>(tex.image)].raw;
  return {im.width, im.height};
}

}  // namespace svbrdf
