#include "mip/mip.h"

#include <algorithm>
#include <cstdio>

#include "base/error.h"
#include "mip/brdf_pyramid.h"
#include "mip/coat_layer.h"
#include "mip/diffuse_transmission.h"
#include "mip/mip_file.h"
#include "mip/mip_lookup.h"
#include "mip/mip_records.h"
#include "mip/param_pyramid.h"
#include "mip/sheen_layer.h"
#include "mip/texel_choice.h"

namespace svbrdf {

struct MipTexture::Pyramids {
  ParamPyramid param;  // level 0 from the start, the coarse levels once a parameter filter is prepared
  BrdfPyramid brdf;
  bool has_brdf = false;
  bool tint = false;  // build the BRDF pyramid tintable

  const ParamTexel& level0(int i, int j) const { return param.texel(0, i, j); }
  void build(TextureFilter filter, const MaterialTexels& level0) {
    if (reads_param_pyramid(filter) && !param.complete()) param.build_coarse_levels();
    if (filter == TextureFilter::brdf && !has_brdf) {
      BrdfBuildOptions o;
      o.tint = tint;
      brdf = BrdfPyramid::build(level0, o);
      has_brdf = true;
    }
  }
};

MipTexture::MipTexture(MipTexture&&) noexcept = default;
MipTexture& MipTexture::operator=(MipTexture&&) noexcept = default;
MipTexture::~MipTexture() = default;

MipTexture::MipTexture(const MaterialTexels& level0, WrapMode wrap_s, WrapMode wrap_t, TextureFilter filter, bool tint)
    : extent_{level0.width, level0.height},
      wrap_s_(wrap_s),
      wrap_t_(wrap_t),
      pyramids_(std::make_unique<Pyramids>()) {
  pyramids_->tint = tint;
  pyramids_->param = ParamPyramid::level0_only(level0);
  pyramids_->build(filter, level0);
}

MipTexture::MipTexture(MipData data, WrapMode wrap_s, WrapMode wrap_t)
    : extent_(data.extent(0)), wrap_s_(wrap_s), wrap_t_(wrap_t), pyramids_(std::make_unique<Pyramids>()) {
  pyramids_->param = std::move(data.param);
  pyramids_->brdf = std::move(data.brdf);
  pyramids_->has_brdf = true;
  pyramids_->tint = pyramids_->brdf.tintable();
}

MipTexture::MipTexture(const MipRecordLayout& layout, std::unique_ptr<const MipRecordSource> source,
                       WrapMode wrap_s, WrapMode wrap_t)
    : extent_(layout.extent), wrap_s_(wrap_s), wrap_t_(wrap_t), records_(std::make_unique<MipRecords>()) {
  records_->layout = layout;
  records_->source = std::move(source);
  records_->grid = layout.radial_grid();
}

void MipTexture::write(const std::filesystem::path& path, const std::string& cache_key) const {
  if (records_)
    throw Error(path.string() + ": a MIP file is written from the pyramids in memory", Error::Kind::internal);
  if (!prepared(TextureFilter::brdf) || !prepared(TextureFilter::param))
    throw Error(path.string() + ": a MIP file needs both pyramids built", Error::Kind::internal);
  write_mip_file(path, pyramids_->param, pyramids_->brdf, cache_key);
}

std::string mip_build_identity(bool tint) {
  // The options MipTexture::prepare builds with (BrdfPyramid::build's defaults but for the tint).
  BrdfBuildOptions o;
  o.tint = tint;
  char text[320];
  std::snprintf(text, sizeof text,
                "mip file %d; lobes %d; tolerance %a; spread %a; peak weight %a; lean share %a; radial %d; recentre %d; "
                "tint %d; coat lobes %d",
                kMipFileVersion, o.reduction.max_lobes, double(o.reduction.tolerance), double(o.reduction.spread_scale),
                o.reduction.peak_weight, o.reduction.lean_peak_share_spread, int(o.radial_correction), int(o.recentre),
                int(o.tint), o.coat_lobes);
  return text;
}

MipRecordLayout MipTexture::record_layout() const {
  if (records_ || !pyramids_->param.complete())
    throw Error("records are made from a complete parameter pyramid in memory", Error::Kind::internal);
  return MipRecordLayout::of(pyramids_->param, pyramids_->has_brdf ? &pyramids_->brdf : nullptr);
}

void MipTexture::encode_records(const MipRecordLayout& layout, int level, int row_begin, int row_end,
                                std::uint32_t* out) const {
  svbrdf::encode_records(layout, pyramids_->param, layout.brdf ? &pyramids_->brdf : nullptr, level, row_begin,
                         row_end, out);
}

void MipTexture::prepare(TextureFilter filter) {
  if (prepared(filter)) return;
  if (records_)
    throw Error("a texture read from records without the BRDF pyramid's cannot build it",
                Error::Kind::internal);
  // The BRDF build reads MaterialTexels: level 0 remade from its one stored copy (the same floats).
  pyramids_->build(filter,
                   filter == TextureFilter::brdf ? pyramids_->param.level0_texels() : MaterialTexels{});
}

bool MipTexture::prepared(TextureFilter filter) const {
  if (records_) return filter != TextureFilter::brdf || records_->layout.brdf;
  if (reads_param_pyramid(filter)) return pyramids_->param.complete();
  return filter != TextureFilter::brdf || pyramids_->has_brdf;
}

glm::ivec2 MipTexture::nearest_texel(glm::vec2 uv) const {
  return {nearest_texel_index(uv.x, extent_.width, wrap_s_),
          nearest_texel_index(uv.y, extent_.height, wrap_t_)};
}

MaterialTexels MipTexture::level0_texels() const {
  if (records_)
    throw Error("the level-0 texels of a texture read from records are not in memory", Error::Kind::internal);
  return pyramids_->param.level0_texels();
}

bool MipTexture::tintable() const { return records_ ? records_->layout.tint : pyramids_->tint; }

Rgb MipTexture::base_color(TextureFilter filter, const Footprint& f) const {
  if (records_) return record_base_color(filter, f);
  if (filter == TextureFilter::level0) {
    const glm::ivec2 t = nearest_texel(f.uv);
    return pyramids_->level0(t.x, t.y).base_color;
  }
  return filter_params(pyramids_->param, f, wrap()).base_color;
}

float MipTexture::level(const Footprint& f) const { return mip_level(extent_, f); }

float mip_level(Extent level0, const Footprint& f) { return filter_level(level0, level_count(level0), f); }

MipTexture::Choice MipTexture::choose(TextureFilter filter, const Footprint& f, const Rgb& tint,
                                      float u) const {
  if (records_) return choose_record(filter, f, tint, u);
  const Pyramids& p = *pyramids_;
  const Choice c = choose_texel(*this, wrap(), filter, f, tint, u, true, p.tint, p.brdf.levels());
  if (c.level >= 1)
    p.brdf.prefetch(c.level, c.i, c.j);
  else if (c.level == 0)
    __builtin_prefetch(&p.level0(c.i, c.j));
  return c;
}

std::span<const Lobe> MipTexture::lobes(const Choice& c, Scratch& scratch) const {
  if (records_) return record_lobes(c, scratch);
  const Pyramids& p = *pyramids_;
  if (c.level < 0) {
    SpecularLayer layer;
    ParamCoat coat;
    AnisotropyLayer aniso;
    float transmission = 0.0f;
    DiffuseTransmissionLayer diffuse_transmission;
    ParamTexel t = filter_params(p.param, c.footprint, wrap(), kMaxProbes, &layer, &coat, &scratch.sheen, &aniso,
                                 &transmission, &diffuse_transmission);
    t.base_color *= c.tint;
    const ParamLobes l = param_lobes(t, c.filter, layer, p.param.has_coat() ? &coat : nullptr,
                                     p.param.has_sheen() ? &scratch.sheen : nullptr,
                                     p.param.has_anisotropy() ? &aniso : nullptr, transmission,
                                     p.param.has_diffuse_transmission() ? &diffuse_transmission : nullptr);
    scratch.lobe[0] = l.base;
    if (l.coated) scratch.coat = l.coat;
    return {scratch.lobe, 1};
  }
  if (c.level >= 1) {
    const std::span<const Lobe> texel = p.brdf.texel(c.level, c.i, c.j);
    if (c.tint == Rgb(1.0f)) return texel;
    const std::size_t n = std::min<std::size_t>(texel.size(), kMaxLobes);
    for (std::size_t k = 0; k < n; ++k) scratch.lobe[k] = tinted(texel[k], c.tint);
    return {scratch.lobe, n};
  }
  // Level 0 (the BRDF pyramid does not hold it twice): the texel's f_eff. With tint 1 the product is
  // exact, so this is level0_lobe of the texel, the BRDF pyramid's level-0 lobe bit for bit.
  const ParamTexel& t = p.level0(c.i, c.j);
  const AnisotropyLayer* aniso = p.param.anisotropy(0, c.i, c.j);
  const float* transmission = p.param.transmission(0, c.i, c.j);
  const SpecularLayer layer = p.param.specular(0, c.i, c.j);
  scratch.lobe[0] = lobe_from_texel(t.base_color * c.tint, t.metallic, t.roughness, t.normal, 1.0f, layer,
                                    aniso ? *aniso : AnisotropyLayer{}, transmission ? *transmission : 0.0f);
  if (const DiffuseTransmissionLayer* d = p.param.diffuse_transmission(0, c.i, c.j))
    add_diffuse_transmission(scratch.lobe[0], t.metallic, layer, transmission ? *transmission : 0.0f, *d);
  if (const ParamCoat* coat = p.param.coat(0, c.i, c.j)) {
    // As exact_reference.h level0_lobe and level0_coat make them.
    scratch.lobe[0].coat = std::clamp(coat->clearcoat, 0.0f, 1.0f);
    scratch.coat = coat_lobe(CoatLayer{coat->clearcoat, coat->roughness, coat->normal});
  }
  if (const SheenLayer* sheen = p.param.sheen(0, c.i, c.j)) scratch.lobe[0].sheen = sheen_share(*sheen);
  return {scratch.lobe, 1};
}

const SheenLayer* MipTexture::sheen(const Choice& c, const Scratch& scratch) const {
  if (records_) return records_->layout.sheen ? &scratch.sheen : nullptr;  // record_lobes decoded it
  const Pyramids& p = *pyramids_;
  if (!p.param.has_sheen()) return nullptr;
  if (c.level < 0) return &scratch.sheen;
  if (c.level >= 1) return &p.brdf.sheen(c.level, c.i, c.j);
  return p.param.sheen(0, c.i, c.j);
}

std::span<const Lobe> MipTexture::coat(const Choice& c, Scratch& scratch) const {
  if (records_) {
    if (!records_->layout.coat) return {};
    if (c.level >= 1) return {scratch.coat_lobe, static_cast<std::size_t>(scratch.coat_count)};
    return {&scratch.coat, 1};
  }
  const Pyramids& p = *pyramids_;
  if (!p.param.has_coat()) return {};
  if (c.level >= 1) return p.brdf.coat(c.level, c.i, c.j).lobes;
  // lobes() made it (a level-0 texel's, or the parameter filters' mean).
  return {&scratch.coat, 1};
}

void MipTexture::lookup(const Choice& c, LobeMixtureBsdf& out) const {
  if (records_) return record_lookup(c, out);
  Scratch scratch;
  const std::span<const Lobe> base = lobes(c, scratch);
  out.assign(base, coat(c, scratch));
  const BrdfPyramid& brdf = pyramids_->brdf;
  out.set_correction(c.level >= 1 ? brdf.correction(c.level, c.i, c.j) : nullptr, &brdf.radial_grid());
  if (const SheenLayer* s = sheen(c, scratch)) out.set_sheen(*s);
}

}  // namespace svbrdf
