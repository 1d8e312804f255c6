// SceneMips::prepare out of core (render/material_mips.h, render/mip_tiles.h): each entry's MIP
// texture opened from its record file, or read from the MIP cache or built, then written to one and
// freed, one entry at a time.
#include <algorithm>

#include "mip/gltf_material.h"
#include "render/material_mips.h"
#include "render/mip_cache_key.h"
#include "render/mip_tiles.h"
#include "render/texel_inputs.h"
#include "textures/material_loader.h"

namespace svbrdf {

void SceneMips::prepare_base_colors_tiled() {
  for (MaterialMip& mip : mips_) {
    if (!mip.base_color_ || mip.base_color_->texture) continue;
    MaterialDesc base;
    base.base_color_texture = mip.base_color_->ref;
    const glm::ivec2 size = textures_.size(base.base_color_texture);
    const std::string key =
        mip_tiles_key(mip_cache_key(scene_, textures_, base, Extent{size.x, size.y}, color_identity_), false);
    const WrapMode s = mip.base_color_->sampler.wrap_s, t = mip.base_color_->sampler.wrap_t;
    std::string warning;
    mip.base_color_->texture = open_mip_tiles(*tiles_, key, false, s, t, &warning);
    if (!warning.empty()) tile_warnings_.push_back(warning);
    if (mip.base_color_->texture) continue;
    const MaterialImages in = material_images(base, [&](const TextureRef& r, bool color) -> SlotImage {
      return {&textures_.image(r, color), color && textures_.linearized(r)};
    });
    const MipTexture built(decode_material_texels(in), s, t, TextureFilter::param);
    textures_.release(base.base_color_texture);
    mip.base_color_->texture = to_mip_tiles(*tiles_, key, built, s, t);
  }
}

void SceneMips::prepare_tiled(TextureFilter filter, SetupProgress* progress) {
  prepare_base_colors_tiled();
  const bool brdf = filter == TextureFilter::brdf;
  std::vector<std::size_t> todo;
  for (std::size_t i = 0; i < mips_.size(); ++i)
    if (!mips_[i].texture_ || !mips_[i].texture_->prepared(filter)) todo.push_back(i);
  if (todo.empty()) return;
  // The textures each entry's build reads, so that their images are released after the last.
  std::vector<std::vector<TextureRef>> reads(todo.size());
  for (std::size_t t = 0; t < todo.size(); ++t)
    for (const TexelInput& in : texel_inputs(mips_[todo[t]].grid_material_))
      if (in.texture && in.texture->present()) reads[t].push_back(*in.texture);
  const auto read_later = [&](std::size_t t, int texture) {
    for (std::size_t u = t + 1; u < todo.size(); ++u)
      for (const TextureRef& r : reads[u])
        if (r.texture == texture) return true;
    return false;
  };
  const SetupProgress::Stage stage(progress,
                                   "opening or building the materials' " + std::string(filter_name(filter)) +
                                       " MIP maps in the texture cache",
                                   todo.size());
  for (std::size_t t = 0; t < todo.size(); ++t) {
    MaterialMip& mip = mips_[todo[t]];
    const std::string key = key_of(todo[t]);
    const WrapMode s = mip.sampler_.wrap_s, w = mip.sampler_.wrap_t;
    // A file with the BRDF pyramid serves every filter; one with the parameter pyramid alone the others.
    std::string warning;
    mip.texture_ = open_mip_tiles(*tiles_, mip_tiles_key(key, true), true, s, w, &warning);
    if (!warning.empty()) tile_warnings_.push_back(std::exchange(warning, {}));
    if (!mip.texture_ && !brdf)
      mip.texture_ = open_mip_tiles(*tiles_, mip_tiles_key(key, false), false, s, w, &warning);
    if (!warning.empty()) tile_warnings_.push_back(warning);
    if (mip.texture_) {
      ++counts_.read;
    } else {
      std::optional<MipData> data = brdf && cache_ ? cache_->load(key) : std::nullopt;
      if (data) {
        mip.texture_.emplace(std::move(*data), s, w);
        ++counts_.read;
      } else {
        build(todo[t], brdf ? TextureFilter::brdf : TextureFilter::param);
        mip.texture_->prepare(TextureFilter::param);  // a file holds the parameter pyramid whole
        ++counts_.built;
      }
      // The pyramids in memory are freed as the texture that reads the file replaces them.
      mip.texture_ = to_mip_tiles(*tiles_, mip_tiles_key(key, brdf), *mip.texture_, s, w);
      if (cache_) cache_->evict();
    }
    for (const TextureRef& r : reads[t])
      if (!read_later(t, r.texture)) textures_.release(r);
    if (progress) progress->step();
  }
}

}  // namespace svbrdf
