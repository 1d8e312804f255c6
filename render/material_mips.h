#pragma once
// The MIP textures of the scene's materials (mip/mip.h, ../shared/spec/brdf-mip.md): for each material
// whose BRDF the MIP lobes model, the level-0 texels of its base color, metallic-roughness and normal
// textures, decoded once from the images the renderer already holds (TextureSet), and one MipTexture
// built from them, looked up in the uv its textures read.
//
// Which materials take part ("active"): those whose BRDF the lobes model — the glTF metallic-
// roughness BRDF with its KHR_materials_specular and KHR_materials_ior layer (lobe.h) and its
// KHR_materials_clearcoat coat (coat_layer.h) and KHR_materials_sheen sheen (sheen_layer.h), with
// KHR_materials_transmission/diffuse_roughness at their defaults and not unlit — and that have at least
// one of the textures their texels read (render/texel_inputs.h: base color, metallic-roughness, normal,
// specular, specular color, with a coat its weight, roughness and normal, with a sheen its colour and
// roughness, with anisotropy its strength and direction). Every other material is shaded by
// SurfaceBsdf with level0 lookups under every filter (an untextured one has nothing to filter); a
// textured one that is left out gets one warning saying why.
//
// One texel grid per material (render/texel_grid.h): the textures it reads are resampled onto the grid
// of one of them, whatever their KHR_texture_transforms, sizes and wrap modes, so each BRDF-averaged
// texel averages parameters known together at every point it covers. Textures on another uv set join
// it when that set is an affine function of the grid's over the material's vertices (identical sets,
// or one the other scaled and offset; render/uv_relation.h): the relation then places every point's
// texels on the grid as a transform does, within 1/1020 of a texel. The grid is exact
// (reproduces every texture's level0 lookup) when the textures' texels are whole blocks of its texels;
// when an offset shifts them by a fraction of a grid texel it holds them displaced by under half of
// one, and hits at level 0 are shaded from the textures themselves (level0_exact). texel_grid.h says
// which mappings it refuses (texels of fractional width, a grid of more than four times the largest
// texture, textures that do not wrap as the grid does where the surface's uv reach past it, uv sets
// that no affine map relates). A base colour texture that cannot join the grid (on an unrelated uv
// set, or refused by it) is held apart: the grid's
// texels take the base colour factor, the pyramid is built tintable, and a lookup tints it by the
// base colour texture filtered on its own (its parameter pyramid: base colour is linear in the BRDF
// (mip/lobe.h tinted), so this is exact wherever the colour and the other parameters vary
// independently over the footprint — the premise of giving them different mappings; a colour that
// follows the other maps' features through another mapping is averaged apart from them). Any other
// texture the grid refuses, or on a uv set unrelated to the rest's, leaves the material out, with a
// warning naming the material, the textures and what they lack (for uv sets, each set's textures and
// how far the best affine fit misses, against the tolerance).
//
// COLOR_0 is the lookups' tint. A material drawn by a primitive whose COLOR_0 is not white has its
// BRDF pyramid built tintable (mip.h; 6 bytes a stored lobe more), found by the scene scan, so brdf
// filters tinted hits as it does the others.
//
// Building: SceneMips::prepare(filter) builds, for every active material in parallel, the texels and
// what the filter reads, once; later calls for other filters add what is missing. Materials with the
// same textures, factors, uv set and transform share one build (render/texel_inputs.h lists what
// enters the texels). Lookups allocate nothing and only read, so any number of threads may call them
// after prepare().
//
// The MIP cache (render/mip_cache.h), when given: the brdf filter's build, the one that takes
// seconds, is read from the cache when an entry of its key is there (no texels are decoded, nothing
// is built), and stored there with both pyramids when it was built. The parameter filters build in
// less time than an entry takes to read, and do not use it.
//
// Out of core (use_tiles, `--texture-cache`): every MIP texture, the base colours held apart among
// them, reads its records from a file of the texture cache (render/mip_tiles.h), so that the MIP data
// resident at once are bounded by its cap. prepare() opens the file of each entry's key when it is
// there (nothing decoded, built or read whole: the render reads tiles as it needs them); else it reads
// the MIP cache's entry or builds, writes the file and frees the pyramids. One entry at a time (each
// build parallel inside), so the set-up holds about one material's build at once, and the images
// TextureSet read back for the builds are released once no later build of the call reads them. A
// brdf file serves every filter; the others build and write the parameter pyramid's alone.
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "mip/mip.h"
#include "gltf/scene.h"
#include "render/mip_cache.h"
#include "render/texel_grid.h"
#include "render/texture_set.h"
#include "base/setup_progress.h"

namespace svbrdf {

// One material's MIP texture and the uv set it is looked up in.
class MaterialMip {
 public:
  // The uv set (TEXCOORD_n) the material's grid reads.
  int uv_set() const { return grid_.uv_set(); }
  // A footprint of the grid's uv set (before the texture transform) carried into texture space:
  // the transform applied to uv and to both derivatives.
  Footprint to_texture(const Footprint& uvset_footprint) const;
  // The map from the grid's texture space to that of the material's texture `r` (render/texel_grid.h
  // A_k), through the relation of their uv sets when they differ.
  TextureAffine texture_map(const TextureRef& r) const;
  // Whether the grid's level-0 texel at a point holds every texture's level0 lookup there (the textures'
  // texels are whole unions of the grid's); otherwise a level-0 hit is shaded from the textures.
  bool level0_exact() const { return level0_exact_; }
  // The texture; SceneMips::prepare must have built it.
  const MipTexture& texture() const { return *texture_; }

  // Whether the base colour texture is held apart from the grid, as a tint (see the file's header);
  // then its uv set, and its colour under `filter` at a footprint of that uv set.
  bool separate_base_color() const { return base_color_.has_value(); }
  int base_color_uv_set() const { return base_color_->ref.uv_set(); }
  Rgb base_color(TextureFilter filter, const Footprint& uvset_footprint) const;

 private:
  friend class SceneMips;
  // A base colour texture held apart: its slot, sampler and its own parameter pyramid.
  struct BaseColorTint {
    TextureRef ref;
    Sampler sampler;
    std::optional<MipTexture> texture;
  };
  TextureRef grid_;  // the slot whose uv set and transform the grid follows
  Sampler sampler_;  // the grid's wrap modes
  Extent extent_{};  // the grid's size (render/texel_grid.h)
  std::vector<TextureAffine> uv_;  // per uv set, the map from the grid's (TexelGrid::uv)
  bool level0_exact_ = true;
  bool tint_ = false;  // drawn with a COLOR_0 tint or a base colour held apart: the BRDF pyramid is tintable
  MaterialDesc grid_material_;  // what the grid's texels are made of: the material, less a base colour held apart
  std::optional<BaseColorTint> base_color_;
  std::optional<MipTexture> texture_;
};

class SceneMips {
 public:
  // Decides which materials take part (cheap: nothing is decoded yet). Both must outlive this.
  SceneMips(const Scene& scene, const TextureSet& textures);
  SceneMips(const SceneMips&) = delete;
  SceneMips& operator=(const SceneMips&) = delete;

  // Reads and stores brdf builds in `cache` (null: none), their keys made with the color config's
  // identity (ColorConfig::identity, the config that decoded the textures). `cache` must outlive this.
  void use_cache(MipCache* cache, std::string color_identity);
  // Out of core: the MIP textures read from files in `tiles` (see the header), their keys made with
  // the color config's identity. `tiles` must outlive this.
  void use_tiles(TextureTiles* tiles, std::string color_identity);
  // How many distinct MIP builds prepare() read from the cache and how many it built (brdf only; out of
  // core, under every filter: the files opened or entries read, and the builds).
  struct CacheCounts {
    int read = 0, built = 0;
  };
  CacheCounts cache_counts() const { return counts_; }

  // Builds what `filter` needs for every active material (nothing for level0 beyond the texels),
  // a step of `progress` (a stage of its own) per material. Thread-safe and idempotent; throws
  // svbrdf::Error (bad input) naming the image when one cannot be decoded into texels.
  void prepare(TextureFilter filter, SetupProgress* progress = nullptr);

  // The MIP data of material `index` (MeshPrimitive::material; −1 is glTF's default material) when
  // it takes part, else null.
  const MaterialMip* find(int index) const {
    if (index < 0 || index >= static_cast<int>(slot_.size())) return nullptr;
    const int slot = slot_[static_cast<std::size_t>(index)];
    return slot < 0 ? nullptr : &mips_[static_cast<std::size_t>(slot)];
  }

  // What a render under `filter` should say, one line each: the textured materials left out (every
  // MIP filter). None for level0.
  std::vector<std::string> warnings(TextureFilter filter) const;
  // Materials that take part, and the distinct MIP data they share (materials that differ only in
  // what the texels do not hold — alpha, emission, double-sidedness — share one).
  int active_count() const;
  int distinct_count() const { return static_cast<int>(mips_.size()); }

 private:
  // prepare()'s steps: the cached builds read (`todo` left with the rest, `keys` with their keys),
  // and one entry's build.
  void read_cached(std::vector<std::size_t>& todo, std::vector<std::string>& keys, SetupProgress* progress);
  void build(std::size_t entry, TextureFilter filter);
  // prepare() out of core (render/scene_mips_tiles.cpp), and the base colours held apart.
  void prepare_tiled(TextureFilter filter, SetupProgress* progress);
  void prepare_base_colors_tiled();
  std::string key_of(std::size_t entry) const;

  const Scene& scene_;
  const TextureSet& textures_;
  std::vector<MaterialMip> mips_;       // distinct MIP data
  std::vector<int> slot_;                // per material: its entry in mips_, −1 when it does not take part
  std::vector<std::size_t> source_;      // per entry: the first material that uses it
  std::vector<std::string> warnings_;        // materials left out
  MipCache* cache_ = nullptr;
  TextureTiles* tiles_ = nullptr;
  std::string color_identity_;
  std::vector<std::string> tile_warnings_;  // record files refused
  CacheCounts counts_;
  std::mutex mutex_;
};

}  // namespace svbrdf
