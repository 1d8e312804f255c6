#include "textures/material_loader.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <cmath>

#include "base/error.h"
#include "textures/normal_map.h"
#include "textures/sampler.h"

namespace svbrdf {

namespace {

void check_factor(float v, bool at_most_one, const std::string& what) {
  if (!std::isfinite(v) || v < 0.0f || (at_most_one && v > 1.0f))
    throw input_error(what, std::string("must be ") + (at_most_one ? "in [0, 1]" : "finite and ≥ 0") + ", got " + std::to_string(v));
}

void for_rows(int height, int width, const auto& body) {
  const int grain = std::max(1, 16384 / std::max(1, width));
  tbb::parallel_for(tbb::blocked_range<int>(0, height, grain), [&](const tbb::blocked_range<int>& r) {
    for (int j = r.begin(); j != r.end(); ++j) body(j);
  });
}

}  // namespace

MaterialTexels decode_material_texels(const MaterialImages& in, const ColorConfig& color) {
  for (int c = 0; c < 3; ++c) check_factor(in.base_color_factor[c], false, "base color factor");
  check_factor(in.metallic_factor, true, "metallic factor");
  check_factor(in.roughness_factor, true, "roughness factor");
  if (!std::isfinite(in.normal_scale)) throw input_error("normal scale", "must be finite");
  check_factor(in.specular_factor, true, "specular factor");
  for (int c = 0; c < 3; ++c) check_factor(in.specular_color_factor[c], false, "specular color factor");
  check_factor(in.clearcoat_factor, true, "clearcoat factor");
  check_factor(in.clearcoat_roughness_factor, true, "clearcoat roughness factor");
  if (!std::isfinite(in.clearcoat_normal_scale)) throw input_error("clearcoat normal scale", "must be finite");
  for (int c = 0; c < 3; ++c) check_factor(in.sheen_color_factor[c], true, "sheen color factor");
  check_factor(in.sheen_roughness_factor, true, "sheen roughness factor");
  check_factor(in.anisotropy_strength, true, "anisotropy strength");
  if (!std::isfinite(in.anisotropy_rotation)) throw input_error("anisotropy rotation", "must be finite");
  check_factor(in.transmission_factor, true, "transmission factor");
  check_factor(in.diffuse_transmission_factor, true, "diffuse transmission factor");
  for (int c = 0; c < 3; ++c) check_factor(in.diffuse_transmission_color_factor[c], true, "diffuse transmission color factor");
  if (!std::isfinite(in.ior) || in.ior < 0.0f) throw input_error("ior", "must be finite and ≥ 0, got " + std::to_string(in.ior));

  // The common size: the first present image sets it, every other must match it.
  const Image* first = nullptr;
  const std::string* first_name = nullptr;
  const auto take = [&](const Image* img, const std::string& name) {
    if (!img) return;
    check_image_size(name, img->width, img->height);
    if (!first) {
      first = img;
      first_name = &name;
    } else if (img->width != first->width || img->height != first->height) {
      throw input_error(name, "size " + std::to_string(img->width) + "x" + std::to_string(img->height) + " differs from " +
                                  *first_name + " (" + std::to_string(first->width) + "x" + std::to_string(first->height) + ")");
    }
  };
  take(in.base_color, in.base_color_name);
  take(in.metallic_roughness, in.metallic_roughness_name);
  take(in.normal, in.normal_name);
  take(in.specular, in.specular_name);
  take(in.specular_color, in.specular_color_name);
  // The coat's images only where it has a weight: a zero factor makes them irrelevant.
  const bool coat = in.clearcoat_factor > 0.0f;
  if (coat) {
    take(in.clearcoat, in.clearcoat_name);
    take(in.clearcoat_roughness, in.clearcoat_roughness_name);
    take(in.clearcoat_normal, in.clearcoat_normal_name);
  }
  // The sheen's likewise, only where its colour factor is not black (the extension's "no sheen").
  const bool sheen = in.sheen_color_factor != glm::vec3(0.0f);
  if (sheen) {
    take(in.sheen_color, in.sheen_color_name);
    take(in.sheen_roughness, in.sheen_roughness_name);
  }
  // The anisotropy's likewise, only where it has a strength (the extension's "isotropic").
  const bool anisotropy = in.anisotropy_strength > 0.0f;
  if (anisotropy) take(in.anisotropy, in.anisotropy_name);
  // The transmission's likewise, only where its factor is not 0 (the extension's "no transmission").
  const bool transmission = in.transmission_factor > 0.0f;
  if (transmission) take(in.transmission, in.transmission_name);
  // The diffuse transmission's likewise, only where its factor is not 0.
  const bool diffuse_transmission = in.diffuse_transmission_factor > 0.0f;
  if (diffuse_transmission) {
    take(in.diffuse_transmission, in.diffuse_transmission_name);
    take(in.diffuse_transmission_color, in.diffuse_transmission_color_name);
  }
  for (const auto& [img, name] : {std::pair{in.normal, &in.normal_name}, std::pair{coat ? in.clearcoat_normal : nullptr, &in.clearcoat_normal_name}})
    if (img && img->channels < 3)
      throw input_error(*name, "a normal map needs RGB channels, this image has " + std::to_string(img->channels));

  MaterialTexels out = first ? MaterialTexels(first->width, first->height) : MaterialTexels(1, 1);
  const glm::vec3 factor(in.base_color_factor);

  if (in.base_color) {
    // Decoded in the texels' own storage (a gray image's value in R, G and B, as glTF reads it), not
    // in a copy of the image.
    const Image& stored = *in.base_color;
    for_rows(out.height, out.width, [&](int j) {
      for (int i = 0; i < out.width; ++i) out.base_color[out.index(i, j)] = glm::vec3(texel(stored, i, j));
    });
    if (!in.base_color_is_linear) color.srgb_texture_to_linear(std::span(out.base_color));
    for_rows(out.height, out.width, [&](int j) {
      for (int i = 0; i < out.width; ++i) out.base_color[out.index(i, j)] *= factor;
    });
  } else {
    std::fill(out.base_color.begin(), out.base_color.end(), factor);
  }

  if (in.metallic_roughness) {
    const Image& mr = *in.metallic_roughness;
    for_rows(out.height, out.width, [&](int j) {
      for (int i = 0; i < out.width; ++i) {
        const glm::vec4 t = texel(mr, i, j);
        out.metallic[out.index(i, j)] = std::clamp(t.b, 0.0f, 1.0f) * in.metallic_factor;
        out.roughness[out.index(i, j)] = std::clamp(t.g, 0.0f, 1.0f) * in.roughness_factor;
      }
    });
  } else {
    std::fill(out.metallic.begin(), out.metallic.end(), in.metallic_factor);
    std::fill(out.roughness.begin(), out.roughness.end(), in.roughness_factor);
  }

  if (in.normal) {
    const Image& nm = *in.normal;
    for_rows(out.height, out.width, [&](int j) {
      for (int i = 0; i < out.width; ++i) out.normal[out.index(i, j)] = decode_normal(glm::vec3(texel(nm, i, j)), in.normal_scale);
    });
  }

  // The specular layer: per texel only where a texture makes it vary.
  out.ior = in.ior;
  out.specular_factor = in.specular_factor;
  out.specular_color_factor = in.specular_color_factor;
  if (in.specular) {
    out.specular.resize(out.size());
    for_rows(out.height, out.width, [&](int j) {
      for (int i = 0; i < out.width; ++i)
        out.specular[out.index(i, j)] = std::clamp(texel(*in.specular, i, j).a * in.specular_factor, 0.0f, 1.0f);
    });
  }
  if (in.specular_color) {
    Image linear = *in.specular_color;
    if (!in.specular_color_is_linear) color.srgb_texture_to_linear(linear);
    out.specular_color.resize(out.size());
    for_rows(out.height, out.width, [&](int j) {
      for (int i = 0; i < out.width; ++i)
        out.specular_color[out.index(i, j)] = glm::vec3(texel(linear, i, j)) * in.specular_color_factor;
    });
  }

  // The sheen: per texel only where a texture makes it vary.
  if (sheen) {
    out.sheen_color_factor = in.sheen_color_factor;
    out.sheen_roughness_factor = in.sheen_roughness_factor;
    if (in.sheen_color) {
      Image linear = *in.sheen_color;
      if (!in.sheen_color_is_linear) color.srgb_texture_to_linear(linear);
      out.sheen_color.resize(out.size());
      for_rows(out.height, out.width, [&](int j) {
        for (int i = 0; i < out.width; ++i)
          out.sheen_color[out.index(i, j)] = glm::vec3(texel(linear, i, j)) * in.sheen_color_factor;
      });
    }
    if (in.sheen_roughness) {
      out.sheen_roughness.resize(out.size());
      for_rows(out.height, out.width, [&](int j) {
        for (int i = 0; i < out.width; ++i)
          out.sheen_roughness[out.index(i, j)] =
              std::clamp(texel(*in.sheen_roughness, i, j).a, 0.0f, 1.0f) * in.sheen_roughness_factor;
      });
    }
  }

  // The anisotropy: per texel only where its texture makes it vary. The texture's RG is a direction in
  // the tangent frame, turned by the rotation (KHR_materials_anisotropy, "anisotropyTexture"); an RG of
  // (0.5, 0.5) has none to normalize, and reads as (1, 0) as render/surface.cpp reads it.
  if (anisotropy) {
    const float c = std::cos(in.anisotropy_rotation), s = std::sin(in.anisotropy_rotation);
    out.anisotropy_factor = in.anisotropy_strength;
    out.anisotropy_direction_factor = glm::vec2(c, s);
    if (in.anisotropy) {
      out.anisotropy.resize(out.size());
      out.anisotropy_direction.resize(out.size());
      for_rows(out.height, out.width, [&](int j) {
        for (int i = 0; i < out.width; ++i) {
          const glm::vec4 a = texel(*in.anisotropy, i, j);
          const glm::vec2 rg(2.0f * a.r - 1.0f, 2.0f * a.g - 1.0f);
          const float len = glm::length(rg);
          const glm::vec2 t = len > 0.0f && std::isfinite(len) ? rg / len : glm::vec2(1.0f, 0.0f);
          out.anisotropy[out.index(i, j)] = std::clamp(a.b, 0.0f, 1.0f) * in.anisotropy_strength;
          out.anisotropy_direction[out.index(i, j)] = glm::vec2(c * t.x - s * t.y, s * t.x + c * t.y);
        }
      });
    }
  }

  // The transmission: per texel only where its texture makes it vary. The product is clamped, not R
  // alone, as SurfaceBsdf clamps the renderer's transmissionFactor · R (an HDR R above 1 can reach 1).
  if (transmission) {
    out.transmission_factor = in.transmission_factor;
    if (in.transmission) {
      out.transmission.resize(out.size());
      for_rows(out.height, out.width, [&](int j) {
        for (int i = 0; i < out.width; ++i)
          out.transmission[out.index(i, j)] =
              std::clamp(texel(*in.transmission, i, j).r * in.transmission_factor, 0.0f, 1.0f);
      });
    }
  }

  // The diffuse transmission: per texel only where its textures make it vary. The share is clamped as
  // SurfaceBsdf clamps the renderer's diffuseTransmissionFactor · A; the colour, as the renderer's, is not.
  if (diffuse_transmission) {
    out.diffuse_transmission_factor = in.diffuse_transmission_factor;
    out.diffuse_transmission_color_factor = in.diffuse_transmission_color_factor;
    if (in.diffuse_transmission) {
      out.diffuse_transmission.resize(out.size());
      for_rows(out.height, out.width, [&](int j) {
        for (int i = 0; i < out.width; ++i)
          out.diffuse_transmission[out.index(i, j)] =
              std::clamp(texel(*in.diffuse_transmission, i, j).a * in.diffuse_transmission_factor, 0.0f, 1.0f);
      });
    }
    if (in.diffuse_transmission_color) {
      Image linear = *in.diffuse_transmission_color;
      if (!in.diffuse_transmission_color_is_linear) color.srgb_texture_to_linear(linear);
      out.diffuse_transmission_color.resize(out.size());
      for_rows(out.height, out.width, [&](int j) {
        for (int i = 0; i < out.width; ++i)
          out.diffuse_transmission_color[out.index(i, j)] =
              glm::vec3(texel(linear, i, j)) * in.diffuse_transmission_color_factor;
      });
    }
  }

  // The clear coat: per texel only where a texture makes it vary.
  if (!coat) return out;
  out.clearcoat_factor = in.clearcoat_factor;
  out.clearcoat_roughness_factor = in.clearcoat_roughness_factor;
  const auto channel = [&](const Image* img, int c, float factor, std::vector<float>& dst) {
    if (!img) return;
    dst.resize(out.size());
    for_rows(out.height, out.width, [&](int j) {
      for (int i = 0; i < out.width; ++i) dst[out.index(i, j)] = std::clamp(texel(*img, i, j)[c], 0.0f, 1.0f) * factor;
    });
  };
  channel(in.clearcoat, 0, in.clearcoat_factor, out.clearcoat);
  channel(in.clearcoat_roughness, 1, in.clearcoat_roughness_factor, out.clearcoat_roughness);
  if (in.clearcoat_normal) {
    out.clearcoat_normal.resize(out.size());
    for_rows(out.height, out.width, [&](int j) {
      for (int i = 0; i < out.width; ++i)
        out.clearcoat_normal[out.index(i, j)] = decode_normal(glm::vec3(texel(*in.clearcoat_normal, i, j)), in.clearcoat_normal_scale);
    });
  }
  return out;
}

}  // namespace svbrdf
