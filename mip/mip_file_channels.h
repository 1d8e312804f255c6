#pragma once
// Private to mip/ (mip_file.cpp, mip_records.cpp): the channels of the MIP file as mip_file.h lists them —
// the parameters', the lobes' by role, the specular, tint and coat layers', the sheen's, the stretch's, the
// transmission's and the diffuse transmission's — and a lobe packed into them and unpacked; and a pixel's
// layout in a level's bytes.
#include <Imath/half.h>
#include <OpenImageIO/typedesc.h>

#include <algorithm>
#include <cstddef>
#include <cstring>
#include <numeric>
#include <string>

#include <array>
#include <cstdint>
#include <iterator>
#include <vector>

#include "mip/lobe.h"
#include "mip/stored_lobe.h"
#include "mip/stored_normal.h"

namespace svbrdf::mip_file_channels {

inline constexpr const char* kParamChannels[8] = {"param.R",         "param.G",   "param.B",   "param.metallic",
                                                  "param.roughness", "param.N.X", "param.N.Y", "param.N.Z"};
// The specular layer's means, where the material's layer is not plain (mip_file.h).
inline constexpr const char* kParamSpecularChannels[4] = {"param.specular", "param.specular.R", "param.specular.G",
                                                          "param.specular.B"};
inline constexpr const char* kIor = "svbrdf:ior";
// The clear coat's means, in every level of a material with a coat (mip_file.h).
inline constexpr const char* kParamCoatChannels[5] = {"param.coat", "param.coat.roughness", "param.coat.N.X",
                                                      "param.coat.N.Y", "param.coat.N.Z"};
// The sheen's means, in every level of a material with a sheen (mip_file.h).
inline constexpr const char* kParamSheenChannels[4] = {"param.sheen.R", "param.sheen.G", "param.sheen.B",
                                                       "param.sheen.roughness"};
// The anisotropy's means, in every level of an anisotropic material (mip_file.h).
inline constexpr const char* kParamAnisotropyChannels[3] = {"param.anisotropy", "param.anisotropy.X",
                                                            "param.anisotropy.Y"};
// The transmission's mean, in every level of a material that transmits (mip_file.h).
inline constexpr const char* kParamTransmissionChannels[1] = {"param.transmission"};
// The diffuse transmission's means, in every level of a material that has one (mip_file.h).
inline constexpr const char* kParamDiffuseTransmissionChannels[4] = {
    "param.diffuseTransmission", "param.diffuseTransmission.R", "param.diffuseTransmission.G",
    "param.diffuseTransmission.B"};
// The attribute (int, on every subimage ≥ 1 of a coated material's file) of a level's coat lobe slots.
inline constexpr const char* kCoatSlots = "svbrdf:coat_slots";

// What a lobe channel holds.
enum class Role {
  weight, diffuse_r, diffuse_g, diffuse_b, f0_r, f0_g, f0_b,
  normal_direction, normal_deficit,  // stored_normal.h
  alpha, shape, skirt,               // stored_lobe.h
  diffuse90_r, diffuse90_g, diffuse90_b, f90,  // the specular layer's (kSpecularLobeChannels)
  f0_tint_r, f0_tint_g, f0_tint_b,             // the tint layer's (kTintLobeChannels)
  coat,                                         // the coat layer's (kCoatShareChannels)
  sheen,                                        // the sheen's (kSheenShareChannels)
  stretch, stretch_dir_hi, stretch_dir_lo,      // the stretch's (kStretchLobeChannels)
  transmission_r, transmission_g, transmission_b, transmission_alpha, transmission_alpha_hi,  // (kTransmissionLobeChannels)
  transmission90_r, transmission90_g, transmission90_b,                // (kTransmission90LobeChannels)
  transmission_stretch, transmission_stretch_dir_hi, transmission_stretch_dir_lo,  // (kTransmissionStretchLobeChannels)
  diffuse_transmission_r, diffuse_transmission_g, diffuse_transmission_b,        // (kDiffuseTransmissionLobeChannels)
  diffuse_transmission90_r, diffuse_transmission90_g, diffuse_transmission90_b,  // (kDiffuseTransmission90LobeChannels)
  count
};
struct LobeChannel {
  const char* suffix;
  Role role;
  OIIO::TypeDesc::BASETYPE format;
};

// A lobe's channels, 26 bytes (kBytesPerLobe): halves but for the normal's octahedral code.
constexpr OIIO::TypeDesc::BASETYPE kHalf = OIIO::TypeDesc::HALF;
constexpr LobeChannel kLobeChannels[] = {
    {"weight", Role::weight, kHalf},
    {"diffuse.R", Role::diffuse_r, kHalf},
    {"diffuse.G", Role::diffuse_g, kHalf},
    {"diffuse.B", Role::diffuse_b, kHalf},
    {"F0.R", Role::f0_r, kHalf},
    {"F0.G", Role::f0_g, kHalf},
    {"F0.B", Role::f0_b, kHalf},
    {"N.dir", Role::normal_direction, OIIO::TypeDesc::UINT},
    {"N.deficit", Role::normal_deficit, kHalf},
    {"alpha", Role::alpha, kHalf},
    {"shape", Role::shape, kHalf},
    {"skirt", Role::skirt, kHalf},
};
// A lobe's channels of the specular layer, 8 bytes (kBytesPerSpecularLayer), in levels where some
// lobe has ρ90 ≠ 0 or F90 ≠ 1.
constexpr LobeChannel kSpecularLobeChannels[] = {
    {"diffuse90.R", Role::diffuse90_r, kHalf},
    {"diffuse90.G", Role::diffuse90_g, kHalf},
    {"diffuse90.B", Role::diffuse90_b, kHalf},
    {"F90", Role::f90, kHalf},
};
// A lobe's channels of the tint layer, 6 bytes (kBytesPerTintLayer), in levels of a tintable pyramid
// where some lobe has f0_tint ≠ 0.
constexpr LobeChannel kTintLobeChannels[] = {
    {"F0tint.R", Role::f0_tint_r, kHalf},
    {"F0tint.G", Role::f0_tint_g, kHalf},
    {"F0tint.B", Role::f0_tint_b, kHalf},
};
// A base lobe's channel of the coat layer, 2 bytes (kBytesPerCoatShare), in levels of a coated material.
constexpr LobeChannel kCoatShareChannels[] = {
    {"coat", Role::coat, kHalf},
};
// A base lobe's channel of the sheen, 2 bytes (kBytesPerSheenShare), in levels of a material with a sheen.
constexpr LobeChannel kSheenShareChannels[] = {
    {"sheen", Role::sheen, kHalf},
};
// A lobe's channels of its stretch, 6 bytes (kBytesPerStretch), in levels where some lobe is stretched:
// ln r as stored_lobe.h codes it, and the direction's 20-bit code (stored_lobe.h) in two halves of 10
// bits each (integers to 1023, exact in a half), so that a lobe's channels stay halves.
constexpr LobeChannel kStretchLobeChannels[] = {
    {"stretch", Role::stretch, kHalf},
    {"stretch.dirHi", Role::stretch_dir_hi, kHalf},
    {"stretch.dirLo", Role::stretch_dir_lo, kHalf},
};
// A lobe's channels of a thin-walled transmission, 10 bytes (kBytesPerTransmission), in levels where some
// lobe transmits: τ, α_T and α_T,hi (stored_lobe.h; α_T 0 where the lobe transmits nothing, α_T,hi 0
// where its shape is GGX).
constexpr LobeChannel kTransmissionLobeChannels[] = {
    {"transmission.R", Role::transmission_r, kHalf},
    {"transmission.G", Role::transmission_g, kHalf},
    {"transmission.B", Role::transmission_b, kHalf},
    {"transmission.alpha", Role::transmission_alpha, kHalf},
    {"transmission.alphaHi", Role::transmission_alpha_hi, kHalf},
};
// τ90, 6 bytes (kBytesPerTransmission90), in levels where some lobe's is not 0.
constexpr LobeChannel kTransmission90LobeChannels[] = {
    {"transmission90.R", Role::transmission90_r, kHalf},
    {"transmission90.G", Role::transmission90_g, kHalf},
    {"transmission90.B", Role::transmission90_b, kHalf},
};
// The transmission's own stretch, 6 bytes (kBytesPerTransmissionStretch), coded as kStretchLobeChannels,
// in levels where some lobe's transmission is stretched.
constexpr LobeChannel kTransmissionStretchLobeChannels[] = {
    {"transmission.stretch", Role::transmission_stretch, kHalf},
    {"transmission.stretch.dirHi", Role::transmission_stretch_dir_hi, kHalf},
    {"transmission.stretch.dirLo", Role::transmission_stretch_dir_lo, kHalf},
};
// A diffuse transmission's τd, 6 bytes (kBytesPerDiffuseTransmission), in levels where some lobe transmits
// diffusely (diffuse_transmission.h), and its τd90, 6 bytes (kBytesPerDiffuseTransmission90), in levels
// where some lobe's is not 0.
constexpr LobeChannel kDiffuseTransmissionLobeChannels[] = {
    {"diffuseTransmission.R", Role::diffuse_transmission_r, kHalf},
    {"diffuseTransmission.G", Role::diffuse_transmission_g, kHalf},
    {"diffuseTransmission.B", Role::diffuse_transmission_b, kHalf},
};
constexpr LobeChannel kDiffuseTransmission90LobeChannels[] = {
    {"diffuseTransmission90.R", Role::diffuse_transmission90_r, kHalf},
    {"diffuseTransmission90.G", Role::diffuse_transmission90_g, kHalf},
    {"diffuseTransmission90.B", Role::diffuse_transmission90_b, kHalf},
};
// A coat lobe's channels, 14 bytes (kBytesPerCoatLobe), named "coatK.<suffix>": a lobe's without its
// colours, which the extension fixes (stored_lobe.h set_coat_colours).
constexpr LobeChannel kCoatLobeChannels[] = {
    {"weight", Role::weight, kHalf},
    {"N.dir", Role::normal_direction, OIIO::TypeDesc::UINT},
    {"N.deficit", Role::normal_deficit, kHalf},
    {"alpha", Role::alpha, kHalf},
    {"shape", Role::shape, kHalf},
    {"skirt", Role::skirt, kHalf},
};
// The attribute (int 1, on every subimage) of a tintable pyramid's file (brdf_pyramid.h tintable).
inline constexpr const char* kTint = "svbrdf:tint";
// The layers a level's lobe slots carry beyond kLobeChannels.
struct LobeLayers {
  bool specular = false, tint = false, coat = false, sheen = false, stretch = false;
  bool transmission = false, transmission90 = false, transmission_stretch = false;
  bool diffuse_transmission = false, diffuse_transmission90 = false;
};
// The channels of a level's lobe slots, with the layers' it has.
inline std::vector<LobeChannel> lobe_channels(const LobeLayers& l) {
  std::vector<LobeChannel> c(std::begin(kLobeChannels), std::end(kLobeChannels));
  const auto add = [&c](bool has, const auto& channels) {
    if (has) c.insert(c.end(), std::begin(channels), std::end(channels));
  };
  add(l.specular, kSpecularLobeChannels);
  add(l.tint, kTintLobeChannels);
  add(l.coat, kCoatShareChannels);
  add(l.sheen, kSheenShareChannels);
  add(l.stretch, kStretchLobeChannels);
  add(l.transmission, kTransmissionLobeChannels);
  add(l.transmission90, kTransmission90LobeChannels);
  add(l.transmission_stretch, kTransmissionStretchLobeChannels);
  add(l.diffuse_transmission, kDiffuseTransmissionLobeChannels);
  add(l.diffuse_transmission90, kDiffuseTransmission90LobeChannels);
  return c;
}
inline std::vector<LobeChannel> coat_lobe_channels() {
  return std::vector<LobeChannel>(std::begin(kCoatLobeChannels), std::end(kCoatLobeChannels));
}



// One texel's channel values by role: floats, and the normal's code.
struct LobeValues {
  std::array<float, static_cast<std::size_t>(Role::count)> v{};
  std::uint32_t direction = 0;
  float& operator[](Role r) { return v[static_cast<std::size_t>(r)]; }
  float operator[](Role r) const { return v[static_cast<std::size_t>(r)]; }
};

inline LobeValues pack_lobe(const Lobe& l) {
  LobeValues out;
  out[Role::weight] = l.weight;
  out[Role::diffuse_r] = l.diffuse.r, out[Role::diffuse_g] = l.diffuse.g, out[Role::diffuse_b] = l.diffuse.b;
  out[Role::f0_r] = l.f0.r, out[Role::f0_g] = l.f0.g, out[Role::f0_b] = l.f0.b;
  out[Role::diffuse90_r] = l.diffuse90.r, out[Role::diffuse90_g] = l.diffuse90.g, out[Role::diffuse90_b] = l.diffuse90.b;
  out[Role::f90] = l.f90;
  out[Role::f0_tint_r] = l.f0_tint.r, out[Role::f0_tint_g] = l.f0_tint.g, out[Role::f0_tint_b] = l.f0_tint.b;
  out[Role::coat] = l.coat;
  out[Role::sheen] = l.sheen;
  out[Role::transmission_r] = l.transmission.r, out[Role::transmission_g] = l.transmission.g, out[Role::transmission_b] = l.transmission.b;
  out[Role::transmission90_r] = l.transmission90.r, out[Role::transmission90_g] = l.transmission90.g;
  out[Role::transmission90_b] = l.transmission90.b;
  // exact, as α's: a stored α_T² is the square of a half or 0
  out[Role::transmission_alpha] = std::sqrt(l.transmission_alpha2);
  out[Role::transmission_alpha_hi] = std::sqrt(l.transmission_alpha2_hi);
  for (int c = 0; c < 3; ++c) {
    out[Role(int(Role::diffuse_transmission_r) + c)] = l.diffuse_transmission[c];
    out[Role(int(Role::diffuse_transmission90_r) + c)] = l.diffuse_transmission90[c];
  }
  const StoredNormal n = store_normal(l.normal);  // exact: the pyramid's normals are decoded codes
  out.direction = n.direction;
  out[Role::normal_deficit] = n.deficit;
  out[Role::alpha] = std::sqrt(l.alpha2);  // exact: a stored α² is the square of a half (round_to_stored)
  out[Role::shape] = lobe_shape_code(l);
  out[Role::skirt] = lobe_skirt_code(l);
  out[Role::stretch] = lobe_stretch_code(l);
  const std::uint32_t dir = lobe_stretch_direction_code(l);
  out[Role::stretch_dir_hi] = static_cast<float>(dir >> 10), out[Role::stretch_dir_lo] = static_cast<float>(dir & 1023u);
  out[Role::transmission_stretch] = lobe_transmission_stretch_code(l);
  const std::uint32_t t_dir = lobe_transmission_stretch_direction_code(l);
  out[Role::transmission_stretch_dir_hi] = static_cast<float>(t_dir >> 10);
  out[Role::transmission_stretch_dir_lo] = static_cast<float>(t_dir & 1023u);
  return out;
}
inline Lobe unpack_lobe(const LobeValues& in) {
  Lobe l;
  l.weight = in[Role::weight];
  l.diffuse = {in[Role::diffuse_r], in[Role::diffuse_g], in[Role::diffuse_b]};
  l.f0 = {in[Role::f0_r], in[Role::f0_g], in[Role::f0_b]};
  l.diffuse90 = {in[Role::diffuse90_r], in[Role::diffuse90_g], in[Role::diffuse90_b]};
  l.f90 = in[Role::f90];
  l.f0_tint = {in[Role::f0_tint_r], in[Role::f0_tint_g], in[Role::f0_tint_b]};
  l.coat = in[Role::coat];
  l.sheen = in[Role::sheen];
  l.transmission = {in[Role::transmission_r], in[Role::transmission_g], in[Role::transmission_b]};
  l.transmission90 = {in[Role::transmission90_r], in[Role::transmission90_g], in[Role::transmission90_b]};
  // A corrupt α_T of 0 or NaN transmits through the lobe's own shape (lobe.h transmission_shape).
  l.transmission_alpha2 = in[Role::transmission_alpha] * in[Role::transmission_alpha];
  l.transmission_alpha2_hi = in[Role::transmission_alpha_hi] * in[Role::transmission_alpha_hi];
  for (int c = 0; c < 3; ++c) {
    l.diffuse_transmission[c] = in[Role(int(Role::diffuse_transmission_r) + c)];
    l.diffuse_transmission90[c] = in[Role(int(Role::diffuse_transmission90_r) + c)];
  }
  l.normal = load_normal(StoredNormal{in.direction, in[Role::normal_deficit]});
  l.alpha2 = in[Role::alpha] * in[Role::alpha];
  set_lobe_shape_code(l, in[Role::shape]);
  set_lobe_skirt_code(l, in[Role::skirt]);
  // Codes outside 0..1023 (a corrupt file; NaN among them) are clamped into it: some direction, never
  // an undefined conversion.
  const auto ten_bits = [](float v) { return v >= 1.0f ? static_cast<std::uint32_t>(std::min(v, 1023.0f)) : 0u; };
  set_lobe_stretch_code(l, in[Role::stretch], (ten_bits(in[Role::stretch_dir_hi]) << 10) | ten_bits(in[Role::stretch_dir_lo]));
  set_lobe_transmission_stretch_code(
      l, in[Role::transmission_stretch],
      (ten_bits(in[Role::transmission_stretch_dir_hi]) << 10) | ten_bits(in[Role::transmission_stretch_dir_lo]));
  return l;
}

// A pixel's channels as the file stores them (OpenEXR's per-channel formats): byte offsets into a
// native pixel, and typed access.
struct NativeLayout {
  std::vector<OIIO::TypeDesc> formats;
  std::vector<std::size_t> offsets;
  std::size_t stride = 0;
  void add(OIIO::TypeDesc f) {
    formats.push_back(f);
    offsets.push_back(stride);
    stride += f.size();
  }
};

inline void put_float(std::byte* px, const NativeLayout& layout, std::size_t c, float v) {
  std::byte* at = px + layout.offsets[c];
  if (layout.formats[c] == OIIO::TypeDesc::HALF) {
    const std::uint16_t bits = Imath::half(v).bits();  // exact: every half channel holds half values
    std::memcpy(at, &bits, 2);
  } else {
    std::memcpy(at, &v, 4);
  }
}
inline void put_uint(std::byte* px, const NativeLayout& layout, std::size_t c, std::uint32_t v) {
  std::memcpy(px + layout.offsets[c], &v, 4);
}

// A channel's value as a float, whatever its stored format; false for a format no MIP file has.
inline bool get_float(const std::byte* at, OIIO::TypeDesc f, float& v) {
  if (f == OIIO::TypeDesc::FLOAT) {
    std::memcpy(&v, at, 4);
  } else if (f == OIIO::TypeDesc::HALF) {
    Imath::half h;
    std::uint16_t bits;
    std::memcpy(&bits, at, 2);
    h.setBits(bits);
    v = h;
  } else if (f == OIIO::TypeDesc::UINT) {
    std::uint32_t u;
    std::memcpy(&u, at, 4);
    v = static_cast<float>(u);
  } else {
    return false;
  }
  return true;
}

// The layout of a pixel whose channels (`formats`, by channel index) lie in the order of their names:
// OpenEXR stores them so and reads them back so, whatever order they were written in, which makes it
// the one order in which a writer and a reader see the same bytes.
inline NativeLayout name_ordered(const std::vector<std::string>& names, const std::vector<OIIO::TypeDesc>& formats) {
  std::vector<std::size_t> by_name(names.size());
  std::iota(by_name.begin(), by_name.end(), std::size_t(0));
  std::sort(by_name.begin(), by_name.end(), [&](std::size_t a, std::size_t b) { return names[a] < names[b]; });
  NativeLayout l;
  l.formats = formats;
  l.offsets.assign(names.size(), 0);
  for (const std::size_t c : by_name) {
    l.offsets[c] = l.stride;
    l.stride += formats[c].size();
  }
  return l;
}


}  // namespace svbrdf::mip_file_channels
