// MipTexture's lookups from records (mip.h, mip_records.h): the same choices and the same lobes as
// the lookups into the pyramids in memory (mip.cpp), each texel decoded from its record into the
// lookup's Scratch.
#include <algorithm>

#include "base/error.h"
#include "mip/coat_layer.h"
#include "mip/diffuse_transmission.h"
#include "mip/mip.h"
#include "mip/mip_lookup.h"
#include "mip/mip_records.h"
#include "mip/sheen_layer.h"
#include "mip/texel_choice.h"

namespace svbrdf {

namespace {

// The parameter texel of a record, and the layers asked for.
struct RecordParams {
  const MipRecords& r;
  mutable ParamTexel texel;
  const ParamTexel& operator()(int level, int i, int j, ParamSpecular* s, ParamCoat* c, SheenLayer* h,
                               AnisotropyLayer* a, float* t, DiffuseTransmissionLayer* d) const {
    decode_params(r.layout, r.source->record(level, i, j), texel, s, c, h, a, t, d);
    return texel;
  }
};

ParamStore store_of(const MipRecordLayout& l) {
  return {l.extent, l.levels, l.ior, l.specular, l.coat, l.sheen, l.anisotropy, l.transmission, l.diffuse_transmission};
}

}  // namespace

MipTexture::Choice MipTexture::choose_record(TextureFilter filter, const Footprint& f, const Rgb& tint,
                                             float u) const {
  // The records' memory is asked for when they are read.
  const MipRecordLayout& l = records_->layout;
  return choose_texel(*this, wrap(), filter, f, tint, u, l.brdf, l.tint, l.levels);
}

std::span<const Lobe> MipTexture::record_lobes(const Choice& c, Scratch& scratch) const {
  const MipRecords& r = *records_;
  const MipRecordLayout& l = r.layout;
  scratch.coat_count = 0;
  scratch.corrected = false;
  if (c.level < 0) {
    SpecularLayer layer;
    ParamCoat coat;
    AnisotropyLayer aniso;
    float transmission = 0.0f;
    DiffuseTransmissionLayer diffuse_transmission;
    ParamTexel t = filter_params_of(store_of(l), RecordParams{r, {}}, c.footprint, wrap(), kMaxProbes, &layer,
                                    &coat, &scratch.sheen, &aniso, &transmission, &diffuse_transmission);
    t.base_color *= c.tint;
    const ParamLobes p = param_lobes(t, c.filter, layer, l.coat ? &coat : nullptr, l.sheen ? &scratch.sheen : nullptr,
                                     l.anisotropy ? &aniso : nullptr, transmission,
                                     l.diffuse_transmission ? &diffuse_transmission : nullptr);
    scratch.lobe[0] = p.base;
    if (p.coated) scratch.coat = p.coat;
    return {scratch.lobe, 1};
  }
  const std::uint32_t* record = r.source->record(c.level, c.i, c.j);
  ParamTexel t;
  ParamSpecular specular;
  ParamCoat coat;
  AnisotropyLayer aniso;
  float transmission = 0.0f;
  DiffuseTransmissionLayer diffuse_transmission;
  decode_params(l, record, t, &specular, &coat, &scratch.sheen, &aniso, &transmission, &diffuse_transmission);
  if (c.level >= 1) {
    const RecordTexel texel =
        decode_brdf(l, c.level, record, scratch.lobe, scratch.coat_lobe, scratch.correction);
    scratch.coat_count = texel.coat_lobes;
    scratch.corrected = texel.corrected;
    const std::size_t n = static_cast<std::size_t>(texel.lobes);
    if (c.tint != Rgb(1.0f))
      for (std::size_t k = 0; k < n; ++k) scratch.lobe[k] = tinted(scratch.lobe[k], c.tint);
    return {scratch.lobe, n};
  }
  // Level 0, as mip.cpp makes its lobe from the parameter pyramid's texel.
  const SpecularLayer layer{specular.specular, specular.color, l.ior};
  scratch.lobe[0] = lobe_from_texel(t.base_color * c.tint, t.metallic, t.roughness, t.normal, 1.0f, layer, aniso,
                                    transmission);
  if (l.diffuse_transmission) add_diffuse_transmission(scratch.lobe[0], t.metallic, layer, transmission, diffuse_transmission);
  if (l.coat) {
    scratch.lobe[0].coat = std::clamp(coat.clearcoat, 0.0f, 1.0f);
    scratch.coat = coat_lobe(CoatLayer{coat.clearcoat, coat.roughness, coat.normal});
  }
  if (l.sheen) scratch.lobe[0].sheen = sheen_share(scratch.sheen);
  return {scratch.lobe, 1};
}

void MipTexture::record_lookup(const Choice& c, LobeMixtureBsdf& out) const {
  Scratch scratch;
  const std::span<const Lobe> base = record_lobes(c, scratch);
  out.assign(base, coat(c, scratch));
  // The correction decoded into the scratch, which ends with this call: the mixture keeps a copy.
  if (c.level >= 1 && scratch.corrected)
    out.set_correction_copy(scratch.correction, &records_->grid);
  else
    out.set_correction(nullptr, &records_->grid);
  if (const SheenLayer* s = sheen(c, scratch)) out.set_sheen(*s);
}

Rgb MipTexture::record_base_color(TextureFilter filter, const Footprint& f) const {
  const MipRecords& r = *records_;
  if (filter == TextureFilter::level0) {
    const glm::ivec2 t = nearest_texel(f.uv);
    ParamTexel p;
    decode_params(r.layout, r.source->record(0, t.x, t.y), p, nullptr, nullptr, nullptr);
    return p.base_color;
  }
  return filter_params_of(store_of(r.layout), RecordParams{r, {}}, f, wrap(), kMaxProbes, nullptr, nullptr,
                          nullptr)
      .base_color;
}

}  // namespace svbrdf
