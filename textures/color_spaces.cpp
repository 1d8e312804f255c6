#include "textures/color_spaces.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <vector>

#include "base/error.h"

namespace OCIO = OCIO_NAMESPACE;

namespace svbrdf {

namespace {

using Vec3 = std::array<double, 3>;
using Mat3 = std::array<Vec3, 3>;  // rows: out = M · in

// Linear Rec.709 (D65) → CIE XYZ: IEC 61966-2-1:1999 §5.2, the matrix of cie_xyz_d65_interchange.
constexpr Mat3 kRec709ToXyz = {{{0.4124, 0.3576, 0.1805}, {0.2126, 0.7152, 0.0722}, {0.0193, 0.1192, 0.9505}}};
// Linear Rec.709 (D65) → ACES2065-1 (AP0 primaries, Bradford adaptation to the ACES white), the space
// of aces_interchange: SMPTE ST 2065-1 primaries, the matrix the ACES configs use.
constexpr Mat3 kRec709ToAp0 = {
    {{0.4397010, 0.3829780, 0.1773350}, {0.0897923, 0.8134230, 0.0967616}, {0.0175440, 0.1115440, 0.8707040}}};

// A space passes a check when every value is within this of the expected one: loose enough for a
// config that samples its curves into LUTs (Blender's sRGB is a 1D LUT) and rounds its matrices to
// four digits, tight enough to tell sRGB from gamma 2.2 (0.0036 apart at 0.5) and Rec.709 from any
// other primaries.
constexpr double kTolerance = 2e-3;

// IEC 61966-2-1 §5.2, the sRGB decoding.
double srgb_decode(double v) { return v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4); }

// from → to on one RGB value; nullopt when the config cannot build the conversion (a LUT file it
// lacks, a display-referred space without a view): such a space plays no part.
std::optional<Vec3> convert(const OCIO::ConstConfigRcPtr& config, const std::string& from, const std::string& to,
                            const Vec3& in) {
  try {
    float rgb[3] = {float(in[0]), float(in[1]), float(in[2])};
    config->getProcessor(from.c_str(), to.c_str())->getDefaultCPUProcessor()->applyRGB(rgb);
    return Vec3{rgb[0], rgb[1], rgb[2]};
  } catch (const OCIO::Exception&) {
    return std::nullopt;
  }
}

bool near(const Vec3& a, const Vec3& b) {
  for (int c = 0; c < 3; ++c)
    if (!(std::abs(a[c] - b[c]) <= kTolerance * std::max(1.0, std::abs(b[c])))) return false;
  return true;
}

// Whether `space` → `interchange` is `m` (half of each primary: a nonlinear space fails there).
bool is_linear_rec709(const OCIO::ConstConfigRcPtr& config, const std::string& space, const std::string& interchange,
                      const Mat3& m) {
  for (int k = 0; k < 3; ++k) {
    Vec3 in{0, 0, 0};
    in[k] = 0.5;
    const auto out = convert(config, space, interchange, in);
    if (!out || !near(*out, Vec3{0.5 * m[0][k], 0.5 * m[1][k], 0.5 * m[2][k]})) return false;
  }
  return true;
}

// Whether `texture` → `linear` decodes each channel alone by the IEC 61966-2-1 curve: the curve and,
// since no channel leaks into another, the same primaries.
bool decodes_srgb(const OCIO::ConstConfigRcPtr& config, const std::string& texture, const std::string& linear) {
  for (double v : {0.02, 0.2, 0.5, 0.8, 1.0})
    for (int k = 0; k < 3; ++k) {
      Vec3 in{0, 0, 0}, expected{0, 0, 0};
      in[k] = v;
      expected[k] = srgb_decode(v);
      const auto out = convert(config, texture, linear, in);
      if (!out || !near(*out, expected)) return false;
    }
  return true;
}

// The config's name for a role's or a color space's name or alias; empty when it has none.
std::string space_named(const OCIO::ConstConfigRcPtr& config, const char* name) {
  const auto cs = config->getColorSpace(name);
  return cs ? cs->getName() : std::string();
}

void add_unique(std::vector<std::string>& list, const std::string& name) {
  if (!name.empty() && std::find(list.begin(), list.end(), name) == list.end()) list.push_back(name);
}

// The active scene-referred color spaces that hold color (not data), in the config's order.
std::vector<std::string> color_spaces(const OCIO::ConstConfigRcPtr& config) {
  std::vector<std::string> names;
  const int n = config->getNumColorSpaces(OCIO::SEARCH_REFERENCE_SPACE_SCENE, OCIO::COLORSPACE_ACTIVE);
  for (int i = 0; i < n; ++i) {
    const char* name = config->getColorSpaceNameByIndex(OCIO::SEARCH_REFERENCE_SPACE_SCENE, OCIO::COLORSPACE_ACTIVE, i);
    if (const auto cs = config->getColorSpace(name); cs && !cs->isData()) names.push_back(name);
  }
  return names;
}

// Names under which configs in the wild (ours, the ACES 1.x and OCIO 2 ACES configs) carry linear
// Rec.709 and the sRGB texture encoding.
constexpr std::array<const char*, 5> kLinearRec709Names = {"Linear Rec.709 (sRGB)", "lin_rec709", "Utility - Linear - sRGB",
                                                          "Linear Rec.709", "lin_srgb"};
constexpr std::array<const char*, 6> kSrgbTextureNames = {
    "sRGB - Texture", "srgb_tx", "Utility - sRGB - Texture", "Input - Generic - sRGB - Texture", "srgb_texture",
    "sRGB"};
// The roles that configs give the sRGB texture encoding, most specific first.
constexpr std::array<const char*, 5> kTextureRoles = {"color_picking", "texture_paint",
                                                     "matte_paint", "default_byte", "default"};

struct Interchange {
  std::string space, role;
  Mat3 from_rec709;
};

// The interchange role that can confirm Rec.709 primaries: aces_interchange, else
// cie_xyz_d65_interchange where it is scene-referred (in OCIO 2's ACES configs it is a display space,
// reached from scene-linear only through a view's tone curve).
std::optional<Interchange> interchange_of(const OCIO::ConstConfigRcPtr& config) {
  for (const auto& [role, m] : {std::pair{OCIO::ROLE_INTERCHANGE_SCENE, kRec709ToAp0},
                                std::pair{OCIO::ROLE_INTERCHANGE_DISPLAY, kRec709ToXyz}}) {
    if (!config->hasRole(role)) continue;
    const auto cs = config->getColorSpace(role);
    if (cs && cs->getReferenceSpaceType() == OCIO::REFERENCE_SPACE_SCENE) return Interchange{cs->getName(), role, m};
  }
  return std::nullopt;
}

}  // namespace

ResolvedColorSpaces resolve_color_spaces(const OCIO::ConstConfigRcPtr& config, const std::string& source) {
  const bool has_roles = config->getNumRoles() > 0;
  const std::optional<Interchange> interchange = interchange_of(config);
  const auto rec709 = [&](const std::string& space) {
    return !interchange || is_linear_rec709(config, space, interchange->space, interchange->from_rec709);
  };

  // Candidates for linear Rec.709, in order of trust; with an interchange role, only those it confirms.
  std::vector<std::string> linear;
  if (has_roles) add_unique(linear, space_named(config, OCIO::ROLE_SCENE_LINEAR));
  for (const char* name : kLinearRec709Names) add_unique(linear, space_named(config, name));
  if (interchange) {
    std::erase_if(linear, [&](const std::string& s) { return !rec709(s); });
    if (linear.empty())
      for (const std::string& s : color_spaces(config))
        if (rec709(s)) {
          linear.push_back(s);
          break;
        }
  }
  if (linear.empty()) {
    std::string what = "OCIO config has no linear Rec.709 color space";
    if (interchange && config->hasRole(OCIO::ROLE_SCENE_LINEAR))
      what += " (its scene_linear role, \"" + space_named(config, OCIO::ROLE_SCENE_LINEAR) + "\", has other primaries by its " +
              interchange->role + " role, and no other space has Rec.709's)";
    else
      what += " (no scene_linear role, and none of \"Linear Rec.709 (sRGB)\", \"lin_rec709\", "
              "\"Utility - Linear - sRGB\", \"Linear Rec.709\")";
    throw input_error(source, what);
  }

  // Candidates for the sRGB texture encoding: the roles, then the names, then every color space.
  std::vector<std::string> texture;
  if (has_roles)
    for (const char* role : kTextureRoles)
      if (config->hasRole(role)) add_unique(texture, space_named(config, role));
  for (const char* name : kSrgbTextureNames) add_unique(texture, space_named(config, name));
  for (const std::string& s : color_spaces(config)) add_unique(texture, s);

  ResolvedColorSpaces r;
  for (const std::string& l : linear) {
    for (const std::string& t : texture)
      if (t != l && decodes_srgb(config, t, l)) {
        r.linear = l, r.srgb_texture = t;
        break;
      }
    if (!r.linear.empty()) break;
  }
  if (r.linear.empty())
    throw input_error(source, "OCIO config has no sRGB texture color space: none of its roles color_picking, "
                              "texture_paint, matte_paint, default nor any of its color spaces decodes into \"" +
                                  linear.front() + "\" by the IEC 61966-2-1 sRGB curve");
  if (config->hasRole(OCIO::ROLE_DATA)) r.data = space_named(config, OCIO::ROLE_DATA);
  for (int i = 0; r.data.empty() && i < config->getNumColorSpaces(); ++i)
    if (const auto cs = config->getColorSpace(config->getColorSpaceNameByIndex(i)); cs && cs->isData()) r.data = cs->getName();
  return r;
}

}  // namespace svbrdf
