#pragma once
// The BRDF-averaging MIP map as a renderer uses it (../shared/spec/brdf-mip.md): one texture's
// level-0 texels and the pyramids built from them, behind one lookup from a texture filter
// (texture_filter.h), a footprint in texture space and a selection number to what the renderer
// shades: a LobeMixtureBsdf in the geometric tangent frame (z = the interpolated normal before any
// normal map, x = the tangent, y = the glTF bitangent), its lobes carrying the normal-mapped normals.
// A renderer includes this header of mip/ (texture_filter.h alone where it needs only the filters'
// names or Footprint); lobe_mixture_bsdf.h, what it shades, comes with it.
//
// The filters:
//   level0  — the nearest level-0 texel at the exact uv (the sampler's wrap modes), f_eff of that
//             texel as brdf-mip.md writes it: one lobe, lobe_from_texel of its parameters. This is
//             bit for bit the BRDF pyramid's level-0 lobe of that texel (exact_reference.h
//             level0_lobe), so level0 and brdf agree exactly wherever brdf selects a level-0 texel.
//   param, toksvig, vmf — trilinear (anisotropic) filtering of the parameter pyramid, one lobe
//             (mip_lookup.h filter_params; param_lobe with the filter's α widening).
//   brdf    — one texel among the filter's taps, chosen with probability equal to its weight by the
//             selection number u (Pharr et al. 2024): that texel's lobes and radial correction.
//
// A tint (glTF's COLOR_0) multiplies base color: exactly under level0 and the parameter filters, and
// under brdf where the texture was built for it (`tint` below; lobe.h tinted: a lobe keeps apart the
// part of F0 the base color tints, 6 bytes a stored lobe). A texture built without it answers a
// tinted brdf lookup as level0 does.
//
// Wrap modes: every filter reads every level with the texture's wrap modes per axis (mip_lookup.h),
// as the sampler reads level 0 (textures/sampler.h): a footprint that crosses a clamped edge repeats
// that edge's texels of its level and never averages in the opposite edge; a mirrored axis mirrors.
//
// Storage: level 0 is held once, a texel's parameters in one half cache line (the parameter pyramid's
// level 0), for level0's lookups and brdf's level-0 taps, which the BRDF pyramid does not hold; the
// parameter pyramid's coarse levels and the BRDF pyramid are built for the filters that read them.
// Lookups allocate nothing and only read, so any number of threads may call them for a prepared filter.
//
// Out of core (mip_records.h): a texture may instead read its texels' records from storage that holds
// them (render/mip_tiles.h: the texture cache's tiles), one record a lookup, decoded into the lookup's
// Scratch. Decoding gives the in-memory pyramids' values bit for bit, so every filter answers as the
// texture that wrote the records; a texture without the BRDF pyramid's records serves level0 and the
// parameter filters.
#include <filesystem>
#include <memory>
#include <span>
#include <string>

#include <glm/glm.hpp>

#include "mip/lobe_mixture_bsdf.h"
#include "mip/pyramid_shape.h"
#include "mip/texture_filter.h"
#include "textures/material_texels.h"
#include "textures/sampler.h"

namespace svbrdf {

struct MipData;  // mip_data.h: what a MIP file holds (mip_file.h)
struct MipRecordLayout;  // mip_records.h
class MipRecordSource;
struct MipRecords;

class MipTexture {
 public:
  // Level 0 from `level0`, read with the wrap modes along u (s) and v (t), and what `filter` reads
  // built from the same texels; with `tint`, the BRDF pyramid is built for tinted lookups
  // (BrdfBuildOptions::tint), for a material drawn with COLOR_0.
  MipTexture(const MaterialTexels& level0, WrapMode wrap_s, WrapMode wrap_t,
             TextureFilter filter = TextureFilter::level0, bool tint = false);
  // Level 0 and both pyramids as a MIP file holds them (read_mip_file, mip_file.h), moved in: every
  // filter is prepared and nothing is built. A MIP file reads back bit-identically, so lookups answer
  // as those of the texture that wrote it.
  MipTexture(MipData data, WrapMode wrap_s, WrapMode wrap_t);
  // Records of `layout` read from `source` (mip_records.h): every filter the records serve is prepared.
  MipTexture(const MipRecordLayout& layout, std::unique_ptr<const MipRecordSource> source, WrapMode wrap_s,
             WrapMode wrap_t);
  MipTexture(MipTexture&&) noexcept;
  MipTexture& operator=(MipTexture&&) noexcept;
  ~MipTexture();

  // Builds what `filter` reads and is not built yet (the parameter pyramid's coarse levels for param,
  // toksvig and vmf, the BRDF pyramid for brdf), from level 0. Not thread-safe: no lookup may run
  // meanwhile.
  void prepare(TextureFilter filter);
  bool prepared(TextureFilter filter) const;

  Extent extent() const { return extent_; }

  // Writes level 0 and both pyramids as a MIP file (mip_file.h; `cache_key` as there); brdf and a
  // parameter filter must be prepared. Throws svbrdf::Error naming the file when it cannot be written.
  void write(const std::filesystem::path& path, const std::string& cache_key = {}) const;

  // The records of what is built (mip_records.h: the parameter pyramid, complete, and the BRDF pyramid
  // when brdf is prepared), for storage that serves lookups from them; and rows [row_begin, row_end)
  // of level `level`'s records. A texture read from records has none to give (internal error).
  MipRecordLayout record_layout() const;
  void encode_records(const MipRecordLayout& layout, int level, int row_begin, int row_end,
                      std::uint32_t* out) const;

  // A lookup in two steps, so that a caller can do other work while the texel's memory arrives (the
  // fetch into a large texture is most of a lookup's cost): choose() picks the texel — brdf's
  // stochastic tap, or level0's nearest texel — and asks for its memory; lookup() reads it.
  // `footprint` is in texture space, `tint` is COLOR_0's rgb, u ∈ [0, 1) the selection number.
  struct Choice {
    TextureFilter filter = TextureFilter::level0;
    Footprint footprint{};
    Rgb tint{1.0f};
    int level = 0;  // the texel chosen; −1: the parameter filters' trilinear taps, read by lookup()
    int i = 0, j = 0;
  };
  Choice choose(TextureFilter filter, const Footprint& footprint, const Rgb& tint, float u) const;
  // Makes `out` the chosen texel's mixture (its coat lobes among it, and its radial correction).
  void lookup(const Choice& choice, LobeMixtureBsdf& out) const;
  void lookup(TextureFilter filter, const Footprint& footprint, const Rgb& tint, float u,
              LobeMixtureBsdf& out) const {
    lookup(choose(filter, footprint, tint, u), out);
  }
  // The chosen texel's lobes: a view into the BRDF pyramid, or into `scratch` (one lobe of level 0
  // or of a parameter filter, or a coarse texel's lobes tinted).
  // Room for those lobes, left uninitialized: a lookup writes only the ones it returns.
  struct Scratch {
    Scratch() {}
    union {
      Lobe lobe[kMaxLobes];
    };
    union {
      Lobe coat;  // a level-0 texel's or a parameter filter's coat lobe
      Lobe coat_lobe[kMaxLobes];  // a coarse texel's coat lobes, decoded from its record
    };
    SheenLayer sheen;  // a parameter filter's mean sheen (sheen()), or a texel's decoded from its record
    // Decoded from a coarse texel's record: its coat lobes' count and its radial correction.
    int coat_count;
    bool corrected;
    union {
      RadialCorrection correction;
    };
  };
  std::span<const Lobe> lobes(const Choice& choice, Scratch& scratch) const;
  std::span<const Lobe> lobes(TextureFilter filter, const Footprint& footprint, const Rgb& tint, float u,
                              Scratch& scratch) const {
    return lobes(choose(filter, footprint, tint, u), scratch);
  }
  // The chosen texel's coat lobes (coat_layer.h; none for a material without a clear coat): a view into
  // the BRDF pyramid, or into `scratch` (level 0's texel coat, or a parameter filter's mean coat,
  // param_coat_lobe). Its base lobes from lobes() carry their coat shares.
  std::span<const Lobe> coat(const Choice& choice, Scratch& scratch) const;
  // The chosen texel's sheen means (sheen_layer.h; null for a material without a sheen): the BRDF
  // pyramid's, a level-0 texel's own, or a parameter filter's mean, which lobes() put into `scratch`.
  // Its base lobes from lobes() carry their sheen shares.
  const SheenLayer* sheen(const Choice& choice, const Scratch& scratch) const;

  // The base colour of the parameter pyramid at a footprint: level0's nearest texel, under every other
  // filter the parameter filters' trilinear taps (base colour is linear in the BRDF, so its average is
  // exact). For a texture that holds a material's base colour apart from its other parameters
  // (render/material_mips.h); the parameter pyramid must be prepared.
  Rgb base_color(TextureFilter filter, const Footprint& footprint) const;

  // Whether brdf answers tinted lookups from its pyramid (built with `tint`, or read from a MIP file
  // built so).
  bool tintable() const;

  // The continuous MIP level λ the filters read at a texture-space footprint.
  float level(const Footprint& footprint) const;
  // The level-0 texel (column, row) nearest to a texture-space uv under the wrap modes.
  glm::ivec2 nearest_texel(glm::vec2 uv) const;
  // Level 0 as MaterialTexels (a copy).
  MaterialTexels level0_texels() const;

 private:
  struct Pyramids;  // mip.cpp: the parameter pyramid (level 0 always) and the BRDF pyramid
  WrapModes wrap() const { return {wrap_s_, wrap_t_}; }
  // The lookups from records (mip_record_lookup.cpp).
  Choice choose_record(TextureFilter filter, const Footprint& footprint, const Rgb& tint, float u) const;
  std::span<const Lobe> record_lobes(const Choice& choice, Scratch& scratch) const;
  void record_lookup(const Choice& choice, LobeMixtureBsdf& out) const;
  Rgb record_base_color(TextureFilter filter, const Footprint& footprint) const;

  Extent extent_{};
  WrapMode wrap_s_ = WrapMode::repeat, wrap_t_ = WrapMode::repeat;
  std::unique_ptr<Pyramids> pyramids_;  // null where the texels are read from records
  std::unique_ptr<MipRecords> records_;
};

// What a MipTexture's build depends on besides its level-0 texels and this code, as text for a cache
// key (render/mip_cache.h): the BRDF build's options (lobes, tolerance, the radial correction, `tint`)
// and the MIP file version.
std::string mip_build_identity(bool tint = false);

// The continuous MIP level λ the filters read at a texture-space footprint on a level-0 image of
// `level0` texels (for a texture without MIP data: the level a filter would read there).
float mip_level(Extent level0, const Footprint& footprint);

}  // namespace svbrdf
