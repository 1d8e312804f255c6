#include "render/material_mips.h"

#include <algorithm>
#include <cmath>

#include <tbb/parallel_for.h>

#include "render/mip_cache_key.h"
#include "mip/gltf_material.h"
#include "render/texel_grid.h"
#include "render/texel_inputs.h"
#include "render/uv_relation.h"
#include "textures/material_loader.h"

namespace svbrdf {

namespace {

// The maps from the grid's texture space to its textures' (render/texel_grid.h), for the MIP cache's
// key: empty when every texture is on the grid's own mapping (the key is then what it always was).
std::vector<double> grid_mappings(const MaterialDesc& m, const MaterialMip& mip) {
  std::vector<double> out;
  bool any = false;
  for (const TexelInput& in : texel_inputs(m)) {
    if (!in.texture || !in.texture->present()) continue;
    const TextureAffine a = mip.texture_map(*in.texture);
    any = any || !a.identity();
    out.insert(out.end(), {a.linear[0][0], a.linear[0][1], a.linear[1][0], a.linear[1][1], a.offset.x, a.offset.y});
  }
  if (!any) out.clear();
  return out;
}

std::string label(const MaterialDesc& m) { return m.where + (m.name.empty() ? "" : " '" + m.name + "'"); }

}  // namespace

namespace {
Footprint transformed(const TextureTransform& t, const Footprint& f) {
  return {t.apply(f.uv), t.apply_linear(f.duv_dx), t.apply_linear(f.duv_dy)};
}
}  // namespace

Footprint MaterialMip::to_texture(const Footprint& f) const { return transformed(grid_.transform, f); }

TextureAffine MaterialMip::texture_map(const TextureRef& r) const {
  const int set = r.uv_set();
  const bool related = set >= 0 && set < static_cast<int>(uv_.size());
  return grid_to_texture(grid_.transform, r.transform, related ? uv_[static_cast<std::size_t>(set)] : TextureAffine{});
}

Rgb MaterialMip::base_color(TextureFilter filter, const Footprint& f) const {
  return base_color_->texture->base_color(filter, transformed(base_color_->ref.transform, f));
}

SceneMips::SceneMips(const Scene& scene, const TextureSet& textures)
    : scene_(scene), textures_(textures), slot_(scene.materials.size(), -1) {
  for (std::size_t i = 0; i < scene.materials.size(); ++i) {
    const MaterialDesc& m = scene.materials[i];
    // The texture slots the texels read (render/texel_inputs.h), those the material fills.
    const std::vector<TexelInput> inputs = texel_inputs(m);
    std::vector<const TexelInput*> slots;
    for (const TexelInput& in : inputs)
      if (in.texture && in.texture->present()) slots.push_back(&in);
    if (slots.empty()) continue;  // untextured: nothing to filter
    std::string why = mip_unsupported(m);
    const bool modelled = why.empty();
    // The grid the textures are resampled onto (render/texel_grid.h), in the uv range the material's
    // primitives reach on the grid's uv set, its textures on other uv sets placed by the relations of
    // the sets (render/uv_relation.h).
    const UvRelations relations(scene, static_cast<int>(i), slots, textures);
    auto choose = [&](const std::vector<const TexelInput*>& s, TexelGrid& g) {
      return choose_texel_grid(m, s, textures, relations, g);
    };
    TexelGrid grid;
    if (modelled) why = choose(slots, grid);
    // A base colour texture that cannot join the grid is held apart, as a tint (see the header); then
    // what keeps the other textures off one grid, if anything, is the reason.
    bool separate_base = false;
    if (!why.empty() && modelled && m.base_color_texture.present() && slots.size() > 1) {
      std::vector<const TexelInput*> rest;
      for (const TexelInput* in : slots)
        if (in->texture != &m.base_color_texture) rest.push_back(in);
      TexelGrid rest_grid;
      why = choose(rest, rest_grid);
      if (why.empty()) {
        separate_base = true;
        slots = std::move(rest);
        grid = rest_grid;
      }
    }
    if (!why.empty()) {
      warnings_.push_back(label(m) + ": " + why + "; it is shaded with level0 lookups under every filter");
      continue;
    }
    const TextureRef& g = *grid.follows->texture;
    const Sampler& gs = textures.sampler(g);
    // Share the data of an earlier material whose texels and lookups would be the same.
    // Their uv ranges may choose different grids for the same textures: the grids must agree too.
    for (std::size_t k = 0; k < mips_.size() && slot_[i] < 0; ++k) {
      const MaterialMip& o = mips_[k];
      if (same_texels(scene.materials[source_[k]], m) && o.grid_.texture == g.texture &&
          same_transform(o.grid_.transform, g.transform) && o.extent_ == grid.extent && o.uv_ == grid.uv &&
          o.base_color_.has_value() == separate_base)
        slot_[i] = static_cast<int>(k);
    }
    if (slot_[i] >= 0) continue;
    MaterialMip& mip = mips_.emplace_back();
    mip.grid_ = g;
    mip.sampler_ = gs;
    mip.extent_ = grid.extent;
    mip.uv_ = grid.uv;
    mip.level0_exact_ = grid.exact;
    mip.grid_material_ = m;
    if (separate_base) {
      mip.grid_material_.base_color_texture = TextureRef{};  // the texels take the factor alone
      mip.base_color_.emplace(MaterialMip::BaseColorTint{m.base_color_texture, textures.sampler(m.base_color_texture), std::nullopt});
      mip.tint_ = true;
    }
    slot_[i] = static_cast<int>(mips_.size()) - 1;
    source_.push_back(i);
  }
  // COLOR_0 that is not white, on a material that takes part: its BRDF pyramid is built tintable
  // (see the header).
  for (const Mesh& mesh : scene.meshes)
    for (const MeshPrimitive& p : mesh.primitives) {
      if (p.colors.empty() || !find(p.material)) continue;
      if (std::any_of(p.colors.begin(), p.colors.end(), [](const glm::vec4& c) { return glm::vec3(c) != glm::vec3(1.0f); }))
        mips_[static_cast<std::size_t>(slot_[static_cast<std::size_t>(p.material)])].tint_ = true;
    }
}

std::vector<std::string> SceneMips::warnings(TextureFilter filter) const {
  std::vector<std::string> out = tile_warnings_;
  if (filter != TextureFilter::level0) out.insert(out.end(), warnings_.begin(), warnings_.end());
  return out;
}

int SceneMips::active_count() const {
  return static_cast<int>(std::count_if(slot_.begin(), slot_.end(), [](int s) { return s >= 0; }));
}

void SceneMips::use_cache(MipCache* cache, std::string color_identity) {
  const std::lock_guard<std::mutex> lock(mutex_);
  cache_ = cache;
  color_identity_ = std::move(color_identity);
}

void SceneMips::use_tiles(TextureTiles* tiles, std::string color_identity) {
  const std::lock_guard<std::mutex> lock(mutex_);
  tiles_ = tiles;
  color_identity_ = std::move(color_identity);
}

void SceneMips::prepare(TextureFilter filter, SetupProgress* progress) {
  const std::lock_guard<std::mutex> lock(mutex_);
  if (tiles_) return prepare_tiled(filter, progress);
  // The base colours held apart (see the header): their own parameter pyramids, whatever the filter
  // (level0 reads their level 0), their texels decoded as the grid's would be. Not cached: a parameter
  // pyramid builds in less time than an entry takes to read.
  tbb::parallel_for(std::size_t(0), mips_.size(), [&](std::size_t i) {
    MaterialMip& mip = mips_[i];
    if (!mip.base_color_ || mip.base_color_->texture) return;
    MaterialDesc base;
    base.base_color_texture = mip.base_color_->ref;
    const MaterialImages in = material_images(base, [&](const TextureRef& r, bool color) -> SlotImage {
      return {&textures_.image(r, color), color && textures_.linearized(r)};
    });
    mip.base_color_->texture.emplace(decode_material_texels(in), mip.base_color_->sampler.wrap_s,
                                     mip.base_color_->sampler.wrap_t, TextureFilter::param);
  });
  std::vector<std::size_t> todo;
  for (std::size_t i = 0; i < mips_.size(); ++i)
    if (!mips_[i].texture_ || !mips_[i].texture_->prepared(filter)) todo.push_back(i);
  if (todo.empty()) return;
  // The builds the cache holds are read instead (see the header); `keys` then names the rest's.
  std::vector<std::string> keys;
  if (cache_ && filter == TextureFilter::brdf) read_cached(todo, keys, progress);
  if (todo.empty()) return;
  // Two materials whose inputs differ only in how they are looked up (uv set, transform) have one key:
  // the first of them stores the entry, so one process never writes one entry twice at once.
  std::vector<char> stores(keys.size(), 1);
  for (std::size_t t = 0; t < keys.size(); ++t)
    for (std::size_t u = 0; u < t && stores[t]; ++u) stores[t] = keys[u] != keys[t];
  const std::string activity = filter == TextureFilter::level0
                                   ? "decoding the materials' texels"
                                   : "building the " + std::string(filter_name(filter)) + " MIP maps of the materials" +
                                         (keys.empty() ? "" : " that the MIP cache does not hold");
  const SetupProgress::Stage stage(progress, activity, todo.size());
  // Materials in parallel; each build is parallel over rows inside (oneTBB nests).
  tbb::parallel_for(std::size_t(0), todo.size(), [&](std::size_t t) {
    MaterialMip& mip = mips_[todo[t]];
    build(todo[t], filter);
    if (!keys.empty() && stores[t]) {
      mip.texture_->prepare(TextureFilter::param);  // an entry holds both pyramids
      cache_->store(keys[t], *mip.texture_);
    }
    if (progress) progress->step();
  }, tbb::simple_partitioner());
  if (!keys.empty()) counts_.built += static_cast<int>(todo.size());
}

void SceneMips::read_cached(std::vector<std::size_t>& todo, std::vector<std::string>& keys, SetupProgress* progress) {
  std::vector<std::string> all(todo.size());
  std::vector<char> read(todo.size(), 0);
  {
    const SetupProgress::Stage stage(progress, "reading the materials' MIP maps from the MIP cache", todo.size());
    tbb::parallel_for(std::size_t(0), todo.size(), [&](std::size_t t) {
      MaterialMip& mip = mips_[todo[t]];
      all[t] = key_of(todo[t]);
      if (std::optional<MipData> data = cache_->load(all[t])) {
        mip.texture_.emplace(std::move(*data), mip.sampler_.wrap_s, mip.sampler_.wrap_t);
        read[t] = 1;
      }
      if (progress) progress->step();
    }, tbb::simple_partitioner());
  }
  std::vector<std::size_t> missed;
  for (std::size_t t = 0; t < todo.size(); ++t) {
    if (read[t]) {
      ++counts_.read;
      continue;
    }
    missed.push_back(todo[t]);
    keys.push_back(std::move(all[t]));
  }
  todo = std::move(missed);
}

std::string SceneMips::key_of(std::size_t entry) const {
  const MaterialMip& mip = mips_[entry];
  return mip_cache_key(scene_, textures_, mip.grid_material_, mip.extent_, color_identity_, mip.tint_,
                       grid_mappings(mip.grid_material_, mip));
}

void SceneMips::build(std::size_t i, TextureFilter filter) {
  MaterialMip& mip = mips_[i];
  if (mip.texture_) {
    mip.texture_->prepare(filter);
    return;
  }
  const MaterialDesc& m = mip.grid_material_;
  // The images as TextureSet holds them (base color already scene-linear: decoded once), each one
  // that is not on the grid already resampled onto it (render/texel_grid.h).
  // Room for every slot's copy up front: image_for hands out pointers into it.
  std::vector<Image> resampled;
  resampled.reserve(texel_inputs(m).size());
  auto image_for = [&](const TextureRef& r, bool color) -> SlotImage {
    const Image& im = textures_.image(r, color);
    const bool linear = color && textures_.linearized(r);
    const TextureAffine to = mip.texture_map(r);
    if (to.identity() && im.width == mip.extent_.width && im.height == mip.extent_.height) return {&im, linear};
    resampled.push_back(resample(im, textures_.sampler(r).wrap(), to, mip.extent_));
    return {&resampled.back(), linear};
  };
  // decode_material_texels' arguments: what render/texel_inputs.h lists.
  const MaterialImages in = material_images(m, image_for);
  mip.texture_.emplace(decode_material_texels(in), mip.sampler_.wrap_s, mip.sampler_.wrap_t, filter, mip.tint_);
}

}  // namespace svbrdf
