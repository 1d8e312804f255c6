#include "mip/mip_records.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <span>
#include <sstream>

#include "mip/lobe_reduction.h"
#include "mip/mip_file_channels.h"

namespace svbrdf {

using mip_file_channels::LobeChannel;
using mip_file_channels::LobeValues;
using mip_file_channels::Role;

namespace {

constexpr const char* kFormat = "svbrdf mip records 5";

// The roles of a lobe's half channels, in the MIP file's order (its direction word comes first).
std::vector<std::uint8_t> half_roles(const std::vector<LobeChannel>& channels) {
  std::vector<std::uint8_t> out;
  for (const LobeChannel& c : channels)
    if (c.role != Role::normal_direction) out.push_back(static_cast<std::uint8_t>(c.role));
  return out;
}
const std::vector<std::uint8_t>& coat_roles() {
  static const std::vector<std::uint8_t> roles = half_roles(mip_file_channels::coat_lobe_channels());
  return roles;
}

std::uint32_t bits_of(float v) { return std::bit_cast<std::uint32_t>(v); }
float float_of(std::uint32_t w) { return std::bit_cast<float>(w); }
std::uint16_t half_bits(float v) { return Imath::half(v).bits(); }  // exact: the lobes hold half values
float half_value(std::uint32_t word, int which) {
  Imath::half h;
  h.setBits(static_cast<std::uint16_t>(which == 0 ? word & 0xFFFF : word >> 16));
  return float(h);
}

// `slots` lobes into `out` (the texel's, then empty ones, all zeros): the direction word, then the
// other channels' halves, two a word.
void put_lobes(std::span<const Lobe> lobes, int slots, const std::vector<std::uint8_t>& roles, int words,
               std::uint32_t* out) {
  std::fill(out, out + std::size_t(slots) * std::size_t(words), 0u);
  const int n = std::min<int>(slots, static_cast<int>(lobes.size()));
  for (int k = 0; k < n; ++k) {
    std::uint32_t* w = out + std::size_t(k) * std::size_t(words);
    const LobeValues v = mip_file_channels::pack_lobe(lobes[static_cast<std::size_t>(k)]);
    w[0] = v.direction;
    for (std::size_t h = 0; h < roles.size(); ++h)
      w[1 + h / 2] |= std::uint32_t(half_bits(v[Role(roles[h])])) << (16 * (h % 2));
  }
}

Lobe get_lobe(const std::uint32_t* w, const std::vector<std::uint8_t>& roles) {
  LobeValues v;
  v[Role::f90] = 1.0f;  // the plain layer's, where the level has no specular channels (as the MIP file)
  v.direction = w[0];
  for (std::size_t h = 0; h < roles.size(); ++h) v[Role(roles[h])] = half_value(w[1 + h / 2], int(h % 2));
  return mip_file_channels::unpack_lobe(v);
}

}  // namespace

MipRecordLayout MipRecordLayout::of(const ParamPyramid& param, const BrdfPyramid* brdf) {
  MipRecordLayout o;
  o.extent = param.level0();
  o.levels = param.levels();
  o.brdf = brdf != nullptr;
  o.specular = !param.specular_level(0).empty();
  o.coat = param.has_coat();
  o.sheen = param.has_sheen();
  o.anisotropy = param.has_anisotropy();
  o.transmission = param.has_transmission();
  o.diffuse_transmission = param.has_diffuse_transmission();
  o.ior = param.ior();
  o.level.resize(static_cast<std::size_t>(o.levels));
  if (!brdf) {
    o.find_roles();
    return o;
  }
  o.tint = brdf->tintable();
  o.max_lobes = brdf->max_lobes();
  bool corrected = false;
  for (int l = 1; l < o.levels; ++l) {
    const BrdfLevel& bl = brdf->level(l);
    Level& v = o.level[static_cast<std::size_t>(l)];
    v.slots = bl.slots;
    v.coat_slots = o.coat ? brdf->coat_level(l).slots : 0;
    v.lobe_specular = bl.specular_layer();
    v.lobe_tint = o.tint && bl.tint_layer();
    v.lobe_stretch = bl.stretch_layer();
    v.lobe_transmission = bl.transmission_layer();
    v.lobe_transmission90 = bl.transmission90_layer();
    v.lobe_transmission_stretch = bl.transmission_stretch_layer();
    v.lobe_diffuse_transmission = bl.diffuse_transmission_layer();
    v.lobe_diffuse_transmission90 = bl.diffuse_transmission90_layer();
    v.radial = !bl.correction.empty();
    corrected |= v.radial;
  }
  if (corrected) o.radial_inner = brdf->radial_grid().inner, o.radial_outer = brdf->radial_grid().outer_deg;
  o.find_roles();
  return o;
}

void MipRecordLayout::find_roles() {
  roles.clear();
  for (const Level& v : level)
    roles.push_back(half_roles(mip_file_channels::lobe_channels(
        {.specular = v.lobe_specular, .tint = v.lobe_tint, .coat = coat, .sheen = sheen, .stretch = v.lobe_stretch,
         .transmission = v.lobe_transmission, .transmission90 = v.lobe_transmission90,
         .transmission_stretch = v.lobe_transmission_stretch, .diffuse_transmission = v.lobe_diffuse_transmission,
         .diffuse_transmission90 = v.lobe_diffuse_transmission90})));
}

int MipRecordLayout::words(int l) const {
  int n = param_words();
  if (!brdf || l == 0) return n;
  const Level& v = level[static_cast<std::size_t>(l)];
  return n + 1 + v.slots * lobe_words(l) + v.coat_slots * kCoatLobeWords + (v.radial ? kCorrectionWords : 0);
}

std::string MipRecordLayout::describe(const std::string& key) const {
  std::ostringstream s;
  s << kFormat << " key " << key << " extent " << extent.width << ' ' << extent.height << " levels " << levels
    << " brdf " << brdf << " tint " << tint << " specular " << specular << " coat " << coat << " sheen "
    << sheen << " anisotropy " << anisotropy << " transmission " << transmission << " diffuse_transmission "
    << diffuse_transmission << " ior " << bits_of(ior)
    << " max_lobes " << max_lobes << " radial " << bits_of(radial_inner) << ' ' << bits_of(radial_outer);
  for (const Level& v : level)
    s << " level " << v.slots << ' ' << v.coat_slots << ' ' << v.lobe_specular << ' ' << v.lobe_tint << ' '
      << v.lobe_stretch << ' ' << v.lobe_transmission << ' ' << v.lobe_transmission90 << ' ' << v.lobe_transmission_stretch << ' '
      << v.lobe_diffuse_transmission << ' ' << v.lobe_diffuse_transmission90 << ' ' << v.radial;
  return s.str();
}

std::optional<MipRecordLayout> MipRecordLayout::parse(const std::string& text, const std::string& key,
                                                      std::string* why) {
  const auto fail = [&](const std::string& what) -> std::optional<MipRecordLayout> {
    if (why) *why = what;
    return std::nullopt;
  };
  if (text.rfind(std::string(kFormat) + " ", 0) != 0)
    return fail("its description is not a MIP record layout");
  std::istringstream s(text.substr(std::strlen(kFormat)));
  MipRecordLayout o;
  std::string word, stored_key;
  std::uint32_t ior = 0, inner = 0, outer = 0;
  const auto expect = [&](const char* name) { return (s >> word) && word == name; };
  const auto flag = [&](bool& b) {
    int v = -1;
    s >> v;
    b = v == 1;
    return v == 0 || v == 1;
  };
  bool ok = expect("key") && (s >> stored_key) && expect("extent") &&
            (s >> o.extent.width >> o.extent.height) && expect("levels") && (s >> o.levels) &&
            expect("brdf") && flag(o.brdf) && expect("tint") && flag(o.tint) && expect("specular") &&
            flag(o.specular) && expect("coat") && flag(o.coat) && expect("sheen") && flag(o.sheen) &&
            expect("anisotropy") && flag(o.anisotropy) && expect("transmission") && flag(o.transmission) &&
            expect("diffuse_transmission") && flag(o.diffuse_transmission) &&
            expect("ior") && (s >> ior) && expect("max_lobes") && (s >> o.max_lobes) && expect("radial") &&
            (s >> inner >> outer);
  if (!ok) return fail("its description is not a MIP record layout");
  if (stored_key != key) return fail("it holds the MIP data of another key (" + stored_key + ")");
  constexpr int kMaxSide = 1 << 16;
  if (!(o.extent.width >= 1 && o.extent.width <= kMaxSide && o.extent.height >= 1 &&
        o.extent.height <= kMaxSide) ||
      o.levels != level_count(o.extent) || !(o.max_lobes >= 1 && o.max_lobes <= kMaxLobes))
    return fail("its layout's sizes do not form a pyramid");
  o.ior = float_of(ior), o.radial_inner = float_of(inner), o.radial_outer = float_of(outer);
  if (!std::isfinite(o.ior) || !(o.radial_inner >= 0.0f && o.radial_inner < 0.5f) ||
      !std::isfinite(o.radial_outer))
    return fail("its layout's ior or radial grid is out of range");
  for (int l = 0; l < o.levels; ++l) {
    Level v;
    if (!expect("level") || !(s >> v.slots >> v.coat_slots) || !flag(v.lobe_specular) || !flag(v.lobe_tint) ||
        !flag(v.lobe_stretch) || !flag(v.lobe_transmission) || !flag(v.lobe_transmission90) ||
        !flag(v.lobe_transmission_stretch) || !flag(v.lobe_diffuse_transmission) ||
        !flag(v.lobe_diffuse_transmission90) || !flag(v.radial))
      return fail("its layout lists fewer levels than it has");
    const bool brdf_level = o.brdf && l > 0;
    if (v.slots < (brdf_level ? 1 : 0) || v.slots > (brdf_level ? kMaxLobes : 0) || v.coat_slots < 0 ||
        v.coat_slots > (brdf_level && o.coat ? kMaxLobes : 0) ||
        (v.radial && !(brdf_level && o.radial_inner > 0.0f)))
      return fail("its layout's level " + std::to_string(l) + " has slots it cannot have");
    o.level.push_back(v);
  }
  if (s >> word) return fail("its layout lists more levels than it has");
  o.find_roles();
  return o;
}

void encode_records(const MipRecordLayout& layout, const ParamPyramid& param, const BrdfPyramid* brdf, int l,
                    int row_begin, int row_end, std::uint32_t* out) {
  const Extent e = param.extent(l);
  const std::size_t words = static_cast<std::size_t>(layout.words(l));
  const bool lobes = layout.brdf && l > 0;
  const MipRecordLayout::Level& v = layout.level[static_cast<std::size_t>(l)];
  const int lobe_words = lobes ? layout.lobe_words(l) : 0;
  for (int j = row_begin; j < row_end; ++j)
    for (int i = 0; i < e.width; ++i) {
      std::uint32_t* w = out + (std::size_t(j - row_begin) * std::size_t(e.width) + std::size_t(i)) * words;
      const ParamTexel& p = param.texel(l, i, j);
      for (const float x : {p.base_color.r, p.base_color.g, p.base_color.b, p.metallic, p.roughness,
                            p.normal.x, p.normal.y, p.normal.z})
        *w++ = bits_of(x);
      const std::size_t t = std::size_t(j) * std::size_t(e.width) + std::size_t(i);
      if (layout.specular) {
        const ParamSpecular& s = param.specular_level(l)[t];
        for (const float x : {s.specular, s.color.r, s.color.g, s.color.b}) *w++ = bits_of(x);
      }
      if (layout.coat) {
        const ParamCoat& c = *param.coat(l, i, j);
        for (const float x : {c.clearcoat, c.roughness, c.normal.x, c.normal.y, c.normal.z})
          *w++ = bits_of(x);
      }
      if (layout.sheen) {
        const SheenLayer& c = *param.sheen(l, i, j);
        for (const float x : {c.color.r, c.color.g, c.color.b, c.roughness}) *w++ = bits_of(x);
      }
      if (layout.anisotropy) {
        const AnisotropyLayer& a = *param.anisotropy(l, i, j);
        for (const float x : {a.strength, a.direction.x, a.direction.y}) *w++ = bits_of(x);
      }
      if (layout.transmission) *w++ = bits_of(*param.transmission(l, i, j));
      if (layout.diffuse_transmission) {
        const DiffuseTransmissionLayer& d = *param.diffuse_transmission(l, i, j);
        for (const float x : {d.share, d.color.r, d.color.g, d.color.b}) *w++ = bits_of(x);
      }
      if (!lobes) continue;
      const std::span<const Lobe> texel = brdf->level(l).texel_lobes(t);
      const std::span<const Lobe> coat_texel =
          layout.coat ? brdf->coat_level(l).texel_lobes(t) : std::span<const Lobe>{};
      const int n = std::min<int>(v.slots, static_cast<int>(texel.size()));
      const int nc = std::min<int>(v.coat_slots, static_cast<int>(coat_texel.size()));
      *w++ = std::uint32_t(n) | (std::uint32_t(nc) << 8);
      put_lobes(texel, v.slots, layout.roles[std::size_t(l)], lobe_words, w);
      w += std::size_t(v.slots) * std::size_t(lobe_words);
      put_lobes(coat_texel, v.coat_slots, coat_roles(), MipRecordLayout::kCoatLobeWords, w);
      w += std::size_t(v.coat_slots) * MipRecordLayout::kCoatLobeWords;
      if (v.radial) {
        const RadialCorrection& c = brdf->level(l).correction[t];
        for (int k = 0; k < RadialGrid::kNodes; k += 2)
          *w++ = std::uint32_t(half_bits(c.ratio[std::size_t(k)])) |
                 (std::uint32_t(half_bits(c.ratio[std::size_t(k) + 1])) << 16);
      }
    }
}

void decode_params(const MipRecordLayout& layout, const std::uint32_t* w, ParamTexel& p,
                   ParamSpecular* specular, ParamCoat* coat, SheenLayer* sheen, AnisotropyLayer* anisotropy,
                   float* transmission, DiffuseTransmissionLayer* diffuse_transmission) {
  p.base_color = {float_of(w[0]), float_of(w[1]), float_of(w[2])};
  p.metallic = float_of(w[3]);
  p.roughness = float_of(w[4]);
  p.normal = {float_of(w[5]), float_of(w[6]), float_of(w[7])};
  w += MipRecordLayout::kParamWords;
  if (layout.specular) {
    if (specular) *specular = {float_of(w[0]), {float_of(w[1]), float_of(w[2]), float_of(w[3])}};
    w += MipRecordLayout::kSpecularWords;
  }
  if (layout.coat) {
    if (coat) *coat = {float_of(w[0]), float_of(w[1]), {float_of(w[2]), float_of(w[3]), float_of(w[4])}};
    w += MipRecordLayout::kCoatWords;
  }
  if (layout.sheen) {
    if (sheen) *sheen = {{float_of(w[0]), float_of(w[1]), float_of(w[2])}, float_of(w[3])};
    w += MipRecordLayout::kSheenWords;
  }
  if (layout.anisotropy) {
    if (anisotropy) *anisotropy = {float_of(w[0]), {float_of(w[1]), float_of(w[2])}};
    w += MipRecordLayout::kAnisotropyWords;
  }
  if (layout.transmission) {
    if (transmission) *transmission = float_of(w[0]);
    w += MipRecordLayout::kTransmissionWords;
  }
  if (layout.diffuse_transmission && diffuse_transmission)
    *diffuse_transmission = {float_of(w[0]), {float_of(w[1]), float_of(w[2]), float_of(w[3])}};
}

RecordTexel decode_brdf(const MipRecordLayout& layout, int l, const std::uint32_t* w, Lobe* lobes,
                        Lobe* coat_lobes, RadialCorrection& correction) {
  RecordTexel out;
  if (!layout.brdf || l < 1) return out;
  const MipRecordLayout::Level& v = layout.level[static_cast<std::size_t>(l)];
  w += layout.param_words();
  // The counts, held to the slots: a corrupt record reads its own slots, no further.
  out.lobes = std::min<int>(int(w[0] & 0xFF), v.slots);
  out.coat_lobes = std::min<int>(int((w[0] >> 8) & 0xFF), v.coat_slots);
  ++w;
  const int lobe_words = layout.lobe_words(l);
  const std::vector<std::uint8_t>& base = layout.roles[std::size_t(l)];
  for (int k = 0; k < out.lobes; ++k) lobes[k] = get_lobe(w + std::size_t(k) * std::size_t(lobe_words), base);
  w += std::size_t(v.slots) * std::size_t(lobe_words);
  for (int k = 0; k < out.coat_lobes; ++k) {
    coat_lobes[k] = get_lobe(w + std::size_t(k) * MipRecordLayout::kCoatLobeWords, coat_roles());
    set_coat_colours(coat_lobes[k]);
  }
  w += std::size_t(v.coat_slots) * MipRecordLayout::kCoatLobeWords;
  if (v.radial) {
    out.corrected = true;
    for (int k = 0; k < RadialGrid::kNodes; ++k)
      correction.ratio[std::size_t(k)] = half_value(w[k / 2], k % 2);
  }
  return out;
}

}  // namespace svbrdf
