#include "textures/color.h"

#include <OpenColorIO/OpenColorIO.h>
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <tuple>
#include <utility>
#include <vector>

#include "base/error.h"
#include "tests/common/temp_dir.h"

namespace svbrdf {
namespace {

using testing::TempDir;

// IEC 61966-2-1:1999 §5.2 (sRGB → linear) and its inverse, written here independently of OCIO.
double iec_decode(double v) { return v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4); }
double iec_encode(double l) { return l <= 0.0031308 ? 12.92 * l : 1.055 * std::pow(l, 1.0 / 2.4) - 0.055; }

constexpr const char* kBlenderConfig = "/usr/share/blender/datafiles/colormanagement/config.ocio";

// A small config in the shape of OCIO 2's ACES configs: scene_linear ACEScg, aces_interchange
// ACES2065-1, the ACES 1.0 SDR output transform as a view, file rules. Its Rec.709 spaces are built
// from IEC 61966-2-1's XYZ matrix and OCIO's built-in AP0 ↔ XYZ transform; of its two sRGB
// encodings, color_picking names the second.
constexpr const char* kAcesStyleConfig = R"(ocio_profile_version: 2.1
roles:
  aces_interchange: ACES2065-1
  color_picking: Encoded BT.709 texture
  color_timing: ACEScct
  compositing_log: ACEScct
  data: Raw
  default: ACES2065-1
  matte_paint: ACEScct
  scene_linear: ACEScg
  texture_paint: ACEScct
file_rules:
  - !<Rule> {name: ACEScg images, colorspace: ACEScg, pattern: "*_acescg", extension: "*"}
  - !<Rule> {name: Default, colorspace: default}
displays:
  sRGB - Display:
    - !<View> {name: ACES 1.0 - SDR Video, view_transform: ACES 1.0 - SDR Video, display_colorspace: sRGB - Display}
    - !<View> {name: Un-tone-mapped, view_transform: Un-tone-mapped, display_colorspace: sRGB - Display}
view_transforms:
  - !<ViewTransform>
    name: ACES 1.0 - SDR Video
    from_scene_reference: !<BuiltinTransform> {style: ACES-OUTPUT - ACES2065-1_to_CIE-XYZ-D65 - SDR-VIDEO_1.0}
  - !<ViewTransform>
    name: Un-tone-mapped
    from_scene_reference: !<BuiltinTransform> {style: UTILITY - ACES-AP0_to_CIE-XYZ-D65_BFD}
display_colorspaces:
  - !<ColorSpace>
    name: sRGB - Display
    isdata: false
    from_display_reference: !<BuiltinTransform> {style: DISPLAY - CIE-XYZ-D65_to_sRGB}
colorspaces:
  - !<ColorSpace>
    name: ACES2065-1
    isdata: false
  - !<ColorSpace>
    name: ACEScg
    isdata: false
    to_scene_reference: !<BuiltinTransform> {style: ACEScg_to_ACES2065-1}
  - !<ColorSpace>
    name: ACEScct
    isdata: false
    to_scene_reference: !<BuiltinTransform> {style: ACEScct_to_ACES2065-1}
  - !<ColorSpace>
    name: Raw
    isdata: true
  - !<ColorSpace>
    name: Scene-linear BT.709
    isdata: false
    to_scene_reference: !<GroupTransform>
      children:
        - !<MatrixTransform> {matrix: [0.4124, 0.3576, 0.1805, 0, 0.2126, 0.7152, 0.0722, 0, 0.0193, 0.1192, 0.9505, 0, 0, 0, 0, 1]}
        - !<BuiltinTransform> {style: UTILITY - ACES-AP0_to_CIE-XYZ-D65_BFD, direction: inverse}
  - !<ColorSpace>
    name: Another BT.709 encoding
    isdata: false
    to_scene_reference: !<ColorSpaceTransform> {src: Encoded BT.709 texture, dst: ACES2065-1}
  - !<ColorSpace>
    name: Encoded BT.709 texture
    isdata: false
    to_scene_reference: !<GroupTransform>
      children:
        - !<ExponentWithLinearTransform> {gamma: 2.4, offset: 0.055}
        - !<ColorSpaceTransform> {src: Scene-linear BT.709, dst: ACES2065-1}
)";

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

// Packed RGB texels decode as the image does, over more texels than one parallel run (16-bit codes,
// each channel its own): the IEC curve within 1e-6, and the image's floats exactly (a MIP map's bytes
// must not depend on which holds the texels).
TEST(Color, PackedTexelsDecodeAsAnImage) {
  const ColorConfig& cfg = ColorConfig::builtin();
  const int n = 3 * 65536 + 7;
  Image img(n, 1, 3);
  std::vector<glm::vec3> texels(static_cast<std::size_t>(n));
  for (int k = 0; k < n; ++k)
    for (int c = 0; c < 3; ++c) img.at(k, 0, c) = texels[static_cast<std::size_t>(k)][c] = float((std::int64_t(k) * (c + 1) * 7919) % 65536) / 65535.0f;
  cfg.srgb_texture_to_linear(img);
  cfg.srgb_texture_to_linear(std::span(texels));
  int differ = 0, off_curve = 0;
  for (int k = 0; k < n; ++k)
    for (int c = 0; c < 3; ++c) {
      const float code = float((std::int64_t(k) * (c + 1) * 7919) % 65536) / 65535.0f;
      differ += texels[static_cast<std::size_t>(k)][c] != img.at(k, 0, c);
      off_curve += std::abs(texels[static_cast<std::size_t>(k)][c] - iec_decode(code)) > 1e-6;
    }
  EXPECT_EQ(differ, 0);
  EXPECT_EQ(off_curve, 0);
}

// An image or texels of 8- and 16-bit codes decode through tables of the processor's output
// (textures/code_tables.h), other values through the processor: either way each channel is bit for
// bit the processor's own value for it (the per-value decode, which takes no table). Every code of
// both widths as OpenImageIO converts them, in every channel and at shuffled places, with values
// that are no code (a code times a factor, off [0, 1], not a number) among them; RGB and RGBA images
// (alpha untouched) and packed texels; the built-in config's curve and Blender's LUT.
TEST(Color, CodeTablesGiveTheProcessorsOwnFloats) {
  std::vector<float> values(65536 + 256);
  std::vector<std::uint16_t> codes16(65536);
  std::vector<std::uint8_t> codes8(256);
  for (int k = 0; k < 65536; ++k) codes16[std::size_t(k)] = std::uint16_t(k);
  for (int k = 0; k < 256; ++k) codes8[std::size_t(k)] = std::uint8_t(k);
  ASSERT_TRUE(OIIO::convert_pixel_values(OIIO::TypeDesc::UINT16, codes16.data(), OIIO::TypeDesc::FLOAT, values.data(), 65536));
  ASSERT_TRUE(OIIO::convert_pixel_values(OIIO::TypeDesc::UINT8, codes8.data(), OIIO::TypeDesc::FLOAT, values.data() + 65536, 256));
  for (const float v : {0.8f * values[30000], 0.9f * values[65536 + 128], std::nextafter(values[40000], 1.0f), -0.25f, 1.5f,
                        1e-30f, std::nanf("")})
    values.push_back(v);
  const std::size_t n = values.size();
  const auto value = [&](std::size_t p, int c) { return values[(p * 7919 * std::size_t(c + 1) + std::size_t(c) * 101) % n]; };
  std::vector<ColorConfig> configs{ColorConfig::builtin()};
  if (std::filesystem::exists(kBlenderConfig)) configs.push_back(ColorConfig::from_file(kBlenderConfig));
  for (const ColorConfig& cfg : configs) {
    Image rgb(int(n), 1, 3), rgba(int(n), 1, 4);
    std::vector<glm::vec3> texels(n);
    for (std::size_t p = 0; p < n; ++p) {
      for (int c = 0; c < 3; ++c) rgb.at(int(p), 0, c) = rgba.at(int(p), 0, c) = texels[p][c] = value(p, c);
      rgba.at(int(p), 0, 3) = value(p, 3);
    }
    cfg.srgb_texture_to_linear(rgb);
    cfg.srgb_texture_to_linear(rgba);
    cfg.srgb_texture_to_linear(std::span(texels));
    int differ = 0;
    const auto same = [](float a, float b) { return std::memcmp(&a, &b, sizeof a) == 0; };
    for (std::size_t p = 0; p < n; ++p) {
      for (int c = 0; c < 3; ++c) {
        const float expected = cfg.srgb_texture_to_linear(value(p, c));
        differ += !same(rgb.at(int(p), 0, c), expected) + !same(rgba.at(int(p), 0, c), expected) + !same(texels[p][c], expected);
      }
      differ += !same(rgba.at(int(p), 0, 3), value(p, 3));
    }
    EXPECT_EQ(differ, 0) << cfg.source();
  }
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
  // An ACES config's scene_linear is ACEScg: with no space of Rec.709 primaries it has no working space.
  std::string aces_only = kAcesStyleConfig;
  aces_only = aces_only.substr(0, aces_only.find("  - !<ColorSpace>\n    name: Scene-linear BT.709"));
  aces_only.replace(aces_only.find("color_picking: Encoded BT.709 texture"), 37, "color_picking: ACEScct");
  expect_refused(write("no_linear.ocio", aces_only), "no linear Rec.709 color space");
  EXPECT_THROW(ColorConfig::from_file(dir / "absent.ocio"), Error);
}

// An ACES-style config (OCIO 2: view transforms, display color spaces, file rules) whose spaces carry
// none of the names the project knows: everything is found through its roles.
TEST(Color, AcesStyleConfigResolvesThroughRoles) {
  const TempDir dir;
  std::ofstream(dir / "aces.ocio") << kAcesStyleConfig;
  const ColorConfig cfg = ColorConfig::from_file(dir / "aces.ocio");
  // scene_linear is ACEScg, which aces_interchange shows is not Rec.709; color_picking decodes by sRGB.
  EXPECT_EQ(cfg.linear_space(), "Scene-linear BT.709");
  EXPECT_EQ(cfg.srgb_texture_space(), "Encoded BT.709 texture");
  EXPECT_EQ(cfg.data_space(), "Raw");
  for (int k = 0; k < 256; k += 15)
    EXPECT_NEAR(cfg.srgb_texture_to_linear(k / 255.0f), iec_decode(k / 255.0), 1e-5) << "code " << k;

  EXPECT_EQ(cfg.default_display(), "sRGB - Display");
  EXPECT_EQ(cfg.default_view(), "ACES 1.0 - SDR Video");
  // The un-tone-mapped view is Rec.709 → AP0 → XYZ → sRGB: the sRGB encoding of the value itself.
  Image gray(1, 1, 3), toned(1, 1, 3);
  gray.pixels = {0.18f, 0.18f, 0.18f};
  toned.pixels = gray.pixels;
  cfg.linear_to_display(gray, "", "Un-tone-mapped");
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(gray.at(0, 0, c), iec_encode(0.18), 2e-3) << c;
  // The ACES output transform darkens mid-gray (the RRT's S-curve): another value, still on screen.
  cfg.linear_to_display(toned);
  EXPECT_GT(std::abs(toned.at(0, 0, 1) - gray.at(0, 0, 1)), 0.02);
  EXPECT_GT(toned.at(0, 0, 1), 0.0f);
  EXPECT_LT(toned.at(0, 0, 1), 1.0f);

  // File rules: a rule of the config's own names ACEScg; the Default rule alone says nothing.
  EXPECT_EQ(cfg.file_color_space("sky_acescg.exr"), "ACEScg");
  EXPECT_EQ(cfg.file_color_space("sky.exr"), "");
  Image red(1, 1, 3);
  red.pixels = {1.0f, 0.0f, 0.0f};
  Image unchanged = red;
  cfg.file_to_linear(red, "sky_acescg.exr");
  // AP1 red in Rec.709: the first column of the ACEScg → Rec.709 matrix (Bradford, ACES white to D65).
  EXPECT_NEAR(red.at(0, 0, 0), 1.70505, 2e-3);
  EXPECT_NEAR(red.at(0, 0, 1), -0.13026, 2e-3);
  EXPECT_NEAR(red.at(0, 0, 2), -0.02400, 2e-3);
  cfg.file_to_linear(unchanged, "sky.exr");
  EXPECT_EQ(unchanged.pixels, (std::vector<float>{1.0f, 0.0f, 0.0f}));
}

// A config without roles is read by the names configs in the wild give the spaces.
TEST(Color, ConfigWithoutRolesResolvesByNames) {
  const TempDir dir;
  std::ofstream(dir / "plain.ocio") << "ocio_profile_version: 2\n"
                                       "file_rules:\n  - !<Rule> {name: Default, colorspace: Linear Rec.709}\n"
                                       "displays:\n  Monitor:\n    - !<View> {name: Plain, colorspace: sRGB}\n"
                                       "colorspaces:\n"
                                       "  - !<ColorSpace>\n    name: Linear Rec.709\n    isdata: false\n"
                                       "  - !<ColorSpace>\n    name: sRGB\n    isdata: false\n"
                                       "    to_scene_reference: !<ExponentWithLinearTransform> {gamma: 2.4, offset: 0.055}\n";
  const ColorConfig cfg = ColorConfig::from_file(dir / "plain.ocio");
  EXPECT_EQ(cfg.linear_space(), "Linear Rec.709");
  EXPECT_EQ(cfg.srgb_texture_space(), "sRGB");
  EXPECT_EQ(cfg.data_space(), "");
  EXPECT_NEAR(cfg.srgb_texture_to_linear(0.5f), 0.214041, 1e-6);
  EXPECT_EQ(cfg.display_view("", ""), (std::pair<std::string, std::string>{"Monitor", "Plain"}));
}

// A display or view the config lacks is bad input naming the option and listing what there is.
TEST(Color, UnknownDisplayOrViewIsBadInput) {
  const ColorConfig& cfg = ColorConfig::builtin();
  EXPECT_EQ(cfg.display_view("", ""), (std::pair<std::string, std::string>{"sRGB", "Standard"}));
  EXPECT_EQ(cfg.display_view("sRGB", "Raw"), (std::pair<std::string, std::string>{"sRGB", "Raw"}));
  for (const auto& [display, view, needle] : {std::tuple{"Cinema", "", "--display Cinema"},
                                             std::tuple{"sRGB", "Filmic", "--view Filmic"}}) {
    try {
      cfg.display_view(display, view);
      ADD_FAILURE() << "no error for " << display << " / " << view;
    } catch (const Error& e) {
      const std::string what = e.what();
      EXPECT_EQ(what.rfind(needle, 0), 0u) << what;
      EXPECT_NE(what.find(std::string(view).empty() ? "\"sRGB\"" : "\"Standard\", \"Raw\""), std::string::npos) << what;
      EXPECT_EQ(what.find('\n'), std::string::npos) << what;
      EXPECT_EQ(e.exit_code(), 2);
    }
  }
}

// Blender's shipped config (OCIO 2, Filmic): scene_linear "Linear", sRGB textures "sRGB" (a LUT),
// data "Non-Color". Its views are checked against OCIO's own display processor from the
// scene_linear role, a path that asks nothing of ColorConfig.
TEST(Color, BlenderConfigAndItsViews) {
  const std::filesystem::path blender = kBlenderConfig;
  if (!std::filesystem::exists(blender)) GTEST_SKIP() << "Blender's OCIO config is not installed at " << blender;
  const ColorConfig cfg = ColorConfig::from_file(blender);
  EXPECT_EQ(cfg.linear_space(), "Linear");
  EXPECT_EQ(cfg.srgb_texture_space(), "sRGB");
  EXPECT_EQ(cfg.data_space(), "Non-Color");
  EXPECT_NEAR(cfg.srgb_texture_to_linear(0.5f), 0.214041, 1e-3);
  EXPECT_EQ(cfg.display_view("", ""), (std::pair<std::string, std::string>{"sRGB", "Standard"}));

  const auto ocio = OCIO_NAMESPACE::Config::CreateFromFile(blender.c_str());
  Image standard(4, 1, 3);
  standard.pixels = {0.01f, 0.02f, 0.03f, 0.18f, 0.18f, 0.18f, 1.0f, 0.5f, 0.25f, 4.0f, 8.0f, 16.0f};
  Image filmic = standard;
  const std::vector<float> linear = standard.pixels;
  cfg.linear_to_display(standard, "sRGB", "Standard");
  cfg.linear_to_display(filmic, "sRGB", "Filmic");
  for (const auto& [view, image] : {std::pair{"Standard", &standard}, std::pair{"Filmic", &filmic}}) {
    const auto cpu = ocio->getProcessor(OCIO_NAMESPACE::ROLE_SCENE_LINEAR, "sRGB", view,
                                        OCIO_NAMESPACE::TRANSFORM_DIR_FORWARD)->getDefaultCPUProcessor();
    for (int p = 0; p < 4; ++p) {
      float rgb[3] = {linear[3 * p], linear[3 * p + 1], linear[3 * p + 2]};
      cpu->applyRGB(rgb);
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(image->at(p, 0, c), rgb[c], 1e-4) << view << " pixel " << p;
    }
  }
  // Standard is the sRGB encoding, above 1 (clipped in 8 bits) for a highlight; Filmic lifts mid-gray
  // (0.18 → 0.50 rather than 0.46) and keeps the highlight below 1.
  EXPECT_NEAR(standard.at(1, 0, 0), iec_encode(0.18), 2e-3);
  EXPECT_GT(filmic.at(1, 0, 0), standard.at(1, 0, 0) + 0.02f);
  EXPECT_GT(standard.at(3, 0, 0), 1.0f);
  EXPECT_LT(filmic.at(3, 0, 0), 1.0f);
}

}  // namespace
}  // namespace svbrdf
