// svbrdf-render's color management as a user meets it: another OCIO config (Blender's), --display and
// --view applied to the PNG and never to the EXR, and a display or view the config lacks refused.
#include <OpenColorIO/OpenColorIO.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "gltf_test_files.h"
#include "render_program.h"
#include "textures/image.h"

namespace svbrdf {
namespace {

namespace fs = std::filesystem;

const fs::path kBlenderConfig = "/usr/share/blender/datafiles/colormanagement/config.ocio";

// A quad under a colored sky, so the frame holds values from dark to above 1, 4×4 at 1 sample.
std::vector<std::string> quad_args(const test::TempDir& dir, const std::string& stem) {
  const fs::path scene = dir.path() / "quad.gltf";
  if (!fs::exists(scene)) dir.write("quad.gltf", test::GltfQuad().json());
  return {scene.string(), "-q", "--float", "--env", "0.05,0.6,3", "--res", "4x4", "--spp", "1", "--mip-cache", "off",
          "-o", (dir.path() / (stem + ".exr")).string()};
}

std::vector<std::string> plus(std::vector<std::string> args, const std::vector<std::string>& more) {
  args.insert(args.end(), more.begin(), more.end());
  return args;
}

TEST(ColorManagement, BlenderConfigViewsChangeThePngNotTheExr) {
  if (!fs::exists(kBlenderConfig)) GTEST_SKIP() << "Blender's OCIO config is not installed at " << kBlenderConfig;
  const test::TempDir dir;
  const std::vector<std::string> ocio = {"--ocio-config", kBlenderConfig.string()};
  for (const char* view : {"Standard", "Filmic"}) {
    const test::RenderRun r = test::render(plus(quad_args(dir, view), plus(ocio, {"--view", view})), dir.path());
    ASSERT_TRUE(r.end.exited && r.end.code == 0) << view << ": " << r.err;
  }

  const Image exr_standard = read_image(dir.path() / "Standard.exr"), exr_filmic = read_image(dir.path() / "Filmic.exr");
  EXPECT_EQ(exr_standard.pixels, exr_filmic.pixels) << "the view changed the scene-linear EXR";

  // Each PNG pixel is OCIO's own display processor (from the scene_linear role) applied to the EXR's
  // value, to 8 bits.
  const auto config = OCIO_NAMESPACE::Config::CreateFromFile(kBlenderConfig.c_str());
  int differing = 0;
  const Image standard = read_image(dir.path() / "Standard.png");
  for (const char* view : {"Standard", "Filmic"}) {
    const Image png = read_image(dir.path() / (std::string(view) + ".png"));
    ASSERT_EQ(png.width, 4);
    ASSERT_EQ(png.height, 4);
    const auto cpu = config->getProcessor(OCIO_NAMESPACE::ROLE_SCENE_LINEAR, "sRGB", view,
                                          OCIO_NAMESPACE::TRANSFORM_DIR_FORWARD)->getDefaultCPUProcessor();
    for (int y = 0; y < 4; ++y)
      for (int x = 0; x < 4; ++x) {
        float rgb[3] = {exr_standard.at(x, y, 0), exr_standard.at(x, y, 1), exr_standard.at(x, y, 2)};
        cpu->applyRGB(rgb);
        for (int c = 0; c < 3; ++c) {
          EXPECT_NEAR(png.at(x, y, c), std::clamp(rgb[c], 0.0f, 1.0f), 0.6f / 255.0f) << view << " " << x << "," << y;
          if (std::string(view) == "Filmic") differing += std::abs(png.at(x, y, c) - standard.at(x, y, c)) > 2.5f / 255.0f;
        }
      }
  }
  // Filmic is another curve: most channels of the frame differ by more than two codes.
  EXPECT_GT(differing, 24);
}

// An unknown display or view: one line naming it, exit 2, nothing written; checked before the scene is read.
TEST(ColorManagement, UnknownDisplayOrViewIsOneLineAndExit2) {
  const test::TempDir dir;
  for (const std::vector<std::string>& bad : {std::vector<std::string>{"--display", "Cinema"},
                                              std::vector<std::string>{"--view", "Filmic"}}) {
    const test::RenderRun r = test::render(plus(quad_args(dir, "o"), bad), dir.path());
    EXPECT_TRUE(r.end.exited && r.end.code == 2) << bad[0] << ": " << r.err;
    EXPECT_EQ(test::line_count(r.err), 1) << r.err;
    EXPECT_NE(r.err.find(bad[bad.size() - 2] + " " + bad.back()), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(dir.path() / "o.exr"));
    EXPECT_FALSE(fs::exists(dir.path() / "o.png"));
  }
}

// The environment's color space comes from the config's file rules (OCIO 2): a map whose name a rule
// matches is converted from that rule's space; one only the Default rule matches is read as
// scene-linear. The rule's space scales the primaries by a diagonal matrix, so what the camera sees
// of the sky is the file's value times the diagonal (the config's own transform, applied by hand).
TEST(ColorManagement, EnvironmentSpaceComesFromTheFileRules) {
  const test::TempDir dir;
  dir.write("rules.ocio", R"(ocio_profile_version: 2
roles:
  scene_linear: Linear Rec.709
  color_picking: sRGB
  data: Raw
  default: Linear Rec.709
file_rules:
  - !<Rule> {name: Scaled skies, colorspace: Scaled primaries, pattern: "*_scaled", extension: "*"}
  - !<Rule> {name: Default, colorspace: default}
displays:
  sRGB:
    - !<View> {name: Standard, colorspace: sRGB}
colorspaces:
  - !<ColorSpace>
    name: Linear Rec.709
    isdata: false
  - !<ColorSpace>
    name: Scaled primaries
    isdata: false
    to_scene_reference: !<MatrixTransform> {matrix: [2, 0, 0, 0, 0, 1, 0, 0, 0, 0, 0.5, 0, 0, 0, 0, 1]}
  - !<ColorSpace>
    name: sRGB
    isdata: false
    to_scene_reference: !<ExponentWithLinearTransform> {gamma: 2.4, offset: 0.055}
  - !<ColorSpace>
    name: Raw
    isdata: true
)");
  // A uniform sky, the same file under two names.
  Image sky(8, 4, 3);
  for (std::size_t k = 0; k < sky.pixels.size(); k += 3) sky.pixels[k] = 0.25f, sky.pixels[k + 1] = 0.5f, sky.pixels[k + 2] = 1.0f;
  for (const char* name : {"sky_scaled.exr", "sky.exr"}) write_image(dir.path() / name, sky, PixelFormat::float32);
  const std::vector<std::string> ocio = {"--ocio-config", (dir.path() / "rules.ocio").string()};
  for (const char* stem : {"sky_scaled", "sky"}) {
    std::vector<std::string> args = plus(quad_args(dir, stem), ocio);
    // The sky in place of quad_args' uniform one; 16×16 so that the frame's corner sees only the sky.
    const auto env = std::find(args.begin(), args.end(), "--env");
    *(env + 1) = (dir.path() / (std::string(stem) + ".exr")).string();
    *(std::find(args.begin(), args.end(), "4x4")) = "16x16";
    const test::RenderRun r = test::render(args, dir.path());
    ASSERT_TRUE(r.end.exited && r.end.code == 0) << stem << ": " << r.err;
  }
  const Image scaled = read_image(dir.path() / "sky_scaled.exr"), plain = read_image(dir.path() / "sky.exr");
  const float want_scaled[3] = {0.5f, 0.5f, 0.5f}, want_plain[3] = {0.25f, 0.5f, 1.0f};
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(scaled.at(0, 0, c), want_scaled[c], 1e-5f) << "channel " << c;
    EXPECT_NEAR(plain.at(0, 0, c), want_plain[c], 1e-5f) << "channel " << c;
  }
}

}  // namespace
}  // namespace svbrdf
