#include "textures/color.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <fstream>

#include "base/error.h"
#include "tests/common/temp_dir.h"

namespace svbrdf {
namespace {

using testing::TempDir;

// IEC 61966-2-1:1999 §5.2 (sRGB → linear) and its inverse, written here independently of OCIO.
double iec_decode(double v) { return v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4); }
double iec_encode(double l) { return l <= 0.0031308 ? 12.92 * l : 1.055 * std::pow(l, 1.0 / 2.4) - 0.055; }

TEST(Color, SrgbDecodeMatchesIec61966At256Points) {
  const ColorConfig& cfg = ColorConfig::builtin();
  Image ramp(256, 1, 3);
  for (int k = 0; k < 256; ++k)
    for (int c = 0; c < 3; ++c) ramp.at(k, 0, c) = float(k) / 255.0f;
  cfg.srgb_texture_to_linear(ramp);
  for (int k = 0; k < 256; ++k) {
    const double expected = iec_decode(k / 255.0);
    EXPECT_NEAR(cfg.srgb_texture_to_linear(float(k) / 255.0f), expected, 1e-6) << "code " << k;
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(ramp.at(k, 0, c), expected, 1e-6) << "code " << k;
  }
  // The figures DEPENDENCIES.md quotes for checking a config.
  EXPECT_NEAR(cfg.srgb_texture_to_linear(0.5f), 0.214041, 1e-6);
  EXPECT_NEAR(cfg.srgb_texture_to_linear(0.04045f), 0.0031308, 1e-6);
}

// sRGB → linear → sRGB returns every 8-bit code, and encoding matches IEC too.
TEST(Color, RoundTripIsIdentityOn8BitCodes) {
  const ColorConfig& cfg = ColorConfig::builtin();
  Image img(256, 1, 3);
  for (int k = 0; k < 256; ++k)
    for (int c = 0; c < 3; ++c) img.at(k, 0, c) = float(k) / 255.0f;
  cfg.srgb_texture_to_linear(img);
  cfg.linear_to_srgb_texture(img);
  for (int k = 0; k < 256; ++k)
    for (int c = 0; c < 3; ++c) {
      EXPECT_NEAR(img.at(k, 0, c), k / 255.0, 1e-6) << "code " << k;
      EXPECT_EQ(std::lround(img.at(k, 0, c) * 255.0f), k) << "code " << k;
    }
  // OCIO's ExponentWithLinearTransform is the C1-continuous curve (toe slope 12.923, break at
  // 0.03929) where IEC rounds its constants (12.92, 0.04045): encoded values differ by at most
  // 1e-5 in the toe (1/400 of an 8-bit code) and by float rounding above it.
  for (double l : {0.0, 0.001, 0.0031308, 0.01, 0.1, 0.5, 1.0})
    EXPECT_NEAR(cfg.linear_to_srgb_texture(float(l)), iec_encode(l), l < 0.004 ? 1e-5 : 1e-6) << l;
}

// Gray images become RGB; alpha passes through untouched; display output is clamped to [0, 1].
TEST(Color, ChannelsAlphaAndDisplay) {
  const ColorConfig& cfg = ColorConfig::builtin();
  Image gray(2, 1, 1);
  gray.at(0, 0, 0) = 0.5f;
  gray.at(1, 0, 0) = 1.0f;
  cfg.srgb_texture_to_linear(gray);
  ASSERT_EQ(gray.channels, 3);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(gray.at(0, 0, c), 0.214041, 1e-6);

  Image rgba(1, 1, 4);
  rgba.pixels = {0.5f, 0.5f, 0.5f, 0.3f};
  cfg.srgb_texture_to_linear(rgba);
  EXPECT_NEAR(rgba.at(0, 0, 0), 0.214041, 1e-6);
  EXPECT_EQ(rgba.at(0, 0, 3), 0.3f);

  Image linear(3, 1, 3);
  linear.pixels = {0.214041f, 0.214041f, 0.214041f, 2.0f, 2.0f, 2.0f, -0.1f, -0.1f, -0.1f};
  cfg.linear_to_display(linear);
  EXPECT_NEAR(linear.at(0, 0, 0), 0.5, 1e-6);
  EXPECT_NEAR(linear.at(1, 0, 0), 1.0, 1e-6);
  EXPECT_NEAR(linear.at(2, 0, 0), 0.0, 1e-6);
  EXPECT_EQ(cfg.default_display(), "sRGB");
  EXPECT_EQ(cfg.default_view(), "Standard");

  // Any two spaces by name or alias: scene-linear → raw is the identity, linear → XYZ is the
  // Rec.709 matrix (white maps to D65: X = 0.9505, Y = 1, Z = 1.089).
  Image white(1, 1, 3);
  white.pixels = {1.0f, 1.0f, 1.0f};
  cfg.convert(white, "lin_rec709", "CIE-XYZ-D65");
  EXPECT_NEAR(white.at(0, 0, 0), 0.95046, 1e-4);
  EXPECT_NEAR(white.at(0, 0, 1), 1.0, 1e-5);
  EXPECT_NEAR(white.at(0, 0, 2), 1.08906, 1e-4);
  EXPECT_THROW(cfg.convert(white, "lin_rec709", "no such space"), Error);
  EXPECT_THROW(cfg.linear_to_display(white, "no such display"), Error);
}

// $OCIO or an explicit path replaces the built-in config; a bad one is bad input naming it.
TEST(Color, ConfigResolution) {
  const TempDir dir;
  const auto write = [&](const std::string& name, std::string_view text) {
    std::ofstream(dir / name) << text;
    return dir / name;
  };
  const auto copy = write("copy.ocio", builtin_ocio_config_text());
  EXPECT_EQ(ColorConfig::resolve().source(), ColorConfig::builtin().source());
  EXPECT_EQ(ColorConfig::resolve(copy).source(), copy.string());
  EXPECT_NEAR(ColorConfig::resolve(copy).srgb_texture_to_linear(0.5f), 0.214041, 1e-6);

  ::setenv("OCIO", copy.c_str(), 1);
  EXPECT_EQ(ColorConfig::resolve().source(), copy.string());
  const auto other = write("other.ocio", builtin_ocio_config_text());
  EXPECT_EQ(ColorConfig::resolve(other).source(), other.string());  // the explicit path wins
  ::setenv("OCIO", (dir / "missing.ocio").c_str(), 1);
  EXPECT_THROW(ColorConfig::resolve(), Error);
  ::unsetenv("OCIO");

  try {
    ColorConfig::from_file(write("broken.ocio", "ocio_profile_version: 2\nroles: [unterminated\n"));
    ADD_FAILURE() << "no error for a broken config";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("broken.ocio"), std::string::npos) << e.what();
    EXPECT_EQ(e.exit_code(), 2);
  }
  // A config with only the given color space (and roles pointing at it).
  const auto minimal = [&](const std::string& file, const std::string& space) {
    return write(file, "ocio_profile_version: 2\nroles:\n  default: " + space + "\n  scene_linear: " + space +
                           "\n  data: " + space + "\ndisplays:\n  d:\n    - !<View> {name: v, colorspace: " + space +
                           "}\ncolorspaces:\n  - !<ColorSpace>\n    name: " + space + "\n    isdata: false\n");
  };
  const auto expect_refused = [](const std::filesystem::path& file, const std::string& needle) {
    try {
      ColorConfig::from_file(file);
      ADD_FAILURE() << "no error for " << file;
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(file.filename().string()), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
      EXPECT_EQ(e.exit_code(), 2);
    }
  };
  expect_refused(minimal("no_srgb.ocio", "lin_rec709"), "no sRGB texture color space");
  expect_refused(minimal("no_linear.ocio", "sRGB - Texture"), "no linear Rec.709 color space");
  EXPECT_THROW(ColorConfig::from_file(dir / "absent.ocio"), Error);
}

}  // namespace
}  // namespace svbrdf
