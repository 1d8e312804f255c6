#pragma once
// Color through OpenColorIO (DESIGN.md, "Data through the house"): color textures (base color,
// emissive) are sRGB-encoded and go sRGB → linear; data textures (normal, metallic-roughness,
// occlusion) stay raw; rendered output goes linear → a display and view of the config. "Linear" is
// the project's working space, linear Rec.709 (DESIGN.md, "Conventions"), whatever the config's
// scene_linear role is: an ACES config renders in ACEScg, but our BRDFs, palettes and MaterialTexels
// are Rec.709. The config's color spaces are found through its roles, checked by what they do
// (textures/color_spaces.h), and by name only where the roles do not give them. The project's own
// config (textures/ocio/config.ocio) is compiled into the library, so an installed binary needs no
// file; $OCIO or an explicit path (the programs' --ocio-config) replaces it: Blender's, an ACES one.
#include <filesystem>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <utility>

#include <glm/glm.hpp>

#include "textures/image.h"

namespace svbrdf {

class CodeTables;  // textures/code_tables.h

class ColorConfig {
 public:
  // The config compiled into the library (textures/ocio/config.ocio).
  static const ColorConfig& builtin();
  // A config file; throws svbrdf::Error naming the file when it is missing or invalid, or when it
  // has no linear Rec.709 or no sRGB texture color space (textures/color_spaces.h).
  static ColorConfig from_file(const std::filesystem::path& path);
  // The config a program should use: `explicit_path` if given, else $OCIO if set and non-empty,
  // else the built-in one.
  static ColorConfig resolve(const std::optional<std::filesystem::path>& explicit_path = std::nullopt);

  // "built-in" or the file's path: for messages.
  const std::string& source() const;
  // The color-space names this config uses for the encodings the project needs.
  const std::string& linear_space() const;  // linear Rec.709, the working space
  const std::string& srgb_texture_space() const;
  const std::string& data_space() const;  // empty when the config has none
  const std::string& default_display() const;
  const std::string& default_view() const;
  // The display and view a display-referred image goes through: an empty display is the config's
  // default display, an empty view that display's default view. Throws bad input naming the option
  // (--display, --view) and listing what the config has when it lacks either.
  std::pair<std::string, std::string> display_view(const std::string& display, const std::string& view) const;
  // What decoding a color texture depends on, as text: the config's content (serialized), the
  // color spaces chosen and the sRGB → linear transform's own identity (OpenColorIO's cache ID, which
  // covers the LUT files it reads). Two configs with the same identity decode texels alike; a key of
  // decoded texels (render/mip_cache.h) hashes it.
  std::string identity() const;

  // In place, channels 0..2 (RGB); an alpha channel passes through unchanged. A gray image (1 or 2
  // channels) is first expanded to RGB(A), as glTF reads gray color textures.
  void srgb_texture_to_linear(Image& image) const;
  void linear_to_srgb_texture(Image& image) const;
  // In place, packed RGB texels (a MaterialTexels colour): the same transform, without an Image.
  void srgb_texture_to_linear(std::span<glm::vec3> rgb) const;
  // The same transform's output for every 8- and 16-bit code (textures/code_tables.h), for a decoder
  // that reads a file's codes rather than its floats; null where the transform has channel crosstalk
  // (every texel then goes through srgb_texture_to_linear).
  const CodeTables* srgb_texture_to_linear_codes() const;
  // Linear Rec.709 → a display/view of the config (empty: its defaults), for rendered output.
  void linear_to_display(Image& image, const std::string& display = {}, const std::string& view = {}) const;
  // Any two color spaces of the config (names or aliases); throws svbrdf::Error for an unknown name.
  void convert(Image& image, const std::string& from, const std::string& to) const;
  // The color space the config's file rules (OCIO 2) give `file`; empty when only the Default rule
  // matches it, which says nothing particular of the file, or the config has no file rules (OCIO 1).
  std::string file_color_space(const std::filesystem::path& file) const;
  // An image whose format leaves its encoding open (an environment map), read from `file`: converted
  // to linear Rec.709 from the space file_color_space gives it; left as read where that is empty, the
  // linear space itself or a data space. glTF fixes its textures' encodings (sRGB color, linear data:
  // glTF 2.0 §3.9), so no rule applies to them.
  void file_to_linear(Image& image, const std::filesystem::path& file) const;

  // Per-value versions for tests and small lookups (through the same processors).
  // The built-in sRGB curve is OCIO's ExponentWithLinearTransform (gamma 2.4, offset 0.055), the
  // C1-continuous form of IEC 61966-2-1: decoded values match the standard's formula within 8e-7,
  // encoded ones within 1e-5 (in the linear toe, where IEC rounds its constants).
  float srgb_texture_to_linear(float v) const;
  float linear_to_srgb_texture(float v) const;

  struct Impl;

 private:
  explicit ColorConfig(std::shared_ptr<const Impl> impl) : impl_(std::move(impl)) {}
  std::shared_ptr<const Impl> impl_;
};

// The text of the built-in config, for tests and for users who want a copy to edit.
std::string_view builtin_ocio_config_text();

}  // namespace svbrdf
