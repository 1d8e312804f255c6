// svbrdf-render --aov: the albedo, normal, depth and MIP level as named layers of the one EXR, which
// OpenImageIO's tools read; no other file is written.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "base/error.h"
#include "gltf_test_files.h"
#include "render_program.h"
#include "textures/image.h"

namespace svbrdf {
namespace {

namespace fs = std::filesystem;

TEST(ExrLayers, TheAovsAreLayersOfTheOneExr) {
  test::TempDir dir;
  const std::string q = dir.write("q.gltf", test::GltfQuad().json()).string();
  const fs::path out = dir.path() / "out";
  const fs::path exr = out / "t.exr";
  const test::RenderRun r = test::render({q, "-q", "--aov", "--res", "24x16", "--spp", "4", "-o", exr.string()}, dir.path());
  ASSERT_TRUE(r.end.exited && r.end.code == 0) << r.err;
  std::vector<std::string> files;
  for (const auto& e : fs::directory_iterator(out)) files.push_back(e.path().filename().string());
  EXPECT_EQ(files.size(), 2u) << "the EXR and the PNG, nothing else";

  const std::string info = test::oiiotool_info(exr, dir.path());
  if (info.find("not found") != std::string::npos) GTEST_SKIP() << "oiiotool is not installed";
  EXPECT_NE(info.find("12 channel"), std::string::npos) << info;
  for (const char* name : {"R", "G", "B", "A", "albedo.R", "albedo.G", "albedo.B", "N.X", "N.Y", "N.Z", "Z", "mip_level.X"})
    EXPECT_NE(info.find(std::string(name) + " ("), std::string::npos) << name << " is not listed: " << info;
  // Depth in float, the rest in half.
  EXPECT_NE(info.find("Z (float)"), std::string::npos) << info;
  EXPECT_NE(info.find("albedo.R (half)"), std::string::npos) << info;

  // The quad lies in the plane z = 0, wound counter-clockwise seen from +z (gltf_test_files.h): where
  // the framing camera sees it, the normal is +z; the corner of the frame sees the environment, with
  // depth 0 (integrator.h).
  const Image n = read_image_channels(exr, {"N.X", "N.Y", "N.Z"}), z = read_image_channels(exr, {"Z"});
  EXPECT_NEAR(n.at(12, 8, 0), 0.0f, 1e-3f);
  EXPECT_NEAR(n.at(12, 8, 1), 0.0f, 1e-3f);
  EXPECT_NEAR(n.at(12, 8, 2), 1.0f, 1e-3f);
  EXPECT_GT(z.at(12, 8, 0), 0.0f);
  EXPECT_EQ(z.at(0, 0, 0), 0.0f);
  EXPECT_EQ(read_image_channels(exr, {"A"}).at(12, 8, 0), 1.0f);
}

TEST(ExrLayers, AChannelTheFileLacksIsNamed) {
  test::TempDir dir;
  const fs::path exr = dir.path() / "plain.exr";
  write_image(exr, Image(2, 2, 3), PixelFormat::half);
  try {
    read_image_channels(exr, {"N.X"});
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("has no channel \"N.X\""), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("plain.exr"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace svbrdf
