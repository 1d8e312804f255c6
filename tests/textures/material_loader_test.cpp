#include "textures/material_loader.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "base/error.h"
#include "tests/common/temp_dir.h"

namespace svbrdf {
namespace {

using testing::TempDir;

double iec_decode(double v) { return v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4); }

Image image_of(int w, int h, int c, std::initializer_list<float> values) {
  Image img(w, h, c);
  img.pixels.assign(values);
  return img;
}

template <class Fn>
void expect_error_naming(Fn fn, const std::vector<std::string>& needles) {
  try {
    fn();
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    for (const std::string& n : needles) EXPECT_NE(std::string(e.what()).find(n), std::string::npos) << e.what();
    EXPECT_EQ(e.exit_code(), 2);
  }
}

// The glTF metallic-roughness decoding, texel by texel, against the formulas written out here:
// base = IEC-decode(code/255)·factor, roughness = G·factor, metallic = B·factor,
// normal = normalize((2·rgb − 1)·(s, s, 1)).
TEST(MaterialLoader, DecodesAGltfTextureSet) {
  const TempDir dir;
  const float c[4] = {0.0f, 64 / 255.0f, 128 / 255.0f, 1.0f};
  write_image(dir / "base.png",
              image_of(2, 2, 3, {c[0], c[1], c[2], c[1], c[2], c[3], c[2], c[3], c[0], c[3], c[0], c[1]}), PixelFormat::uint8);
  write_image(dir / "mr.png", image_of(2, 2, 3, {1, 0.2f, 0.0f, 1, 0.4f, 1.0f, 1, 0.6f, 0.5f, 1, 1.0f, 0.25f}), PixelFormat::uint16);
  write_image(dir / "normal.png",
              image_of(2, 2, 3, {0.5f, 0.5f, 1.0f, 0.8f, 0.5f, 0.9f, 0.5f, 0.8f, 0.9f, 0.2f, 0.5f, 0.9f}), PixelFormat::uint16);
  MaterialFiles files;
  files.base_color = dir / "base.png";
  files.base_color_factor = {0.5f, 1.0f, 0.8f, 1.0f};
  files.metallic_roughness = dir / "mr.png";
  files.metallic_factor = 0.5f;
  files.roughness_factor = 0.9f;
  files.normal = dir / "normal.png";
  files.normal_scale = 2.0f;
  const MaterialTexels t = load_material_texels(files);
  ASSERT_EQ(t.width, 2);
  ASSERT_EQ(t.height, 2);
  const double codes[4][3] = {{0, 64, 128}, {64, 128, 255}, {128, 255, 0}, {255, 0, 64}};
  const double rough[4] = {0.2, 0.4, 0.6, 1.0}, metal[4] = {0.0, 1.0, 0.5, 0.25};
  const glm::vec3 rgb[4] = {{0.5f, 0.5f, 1.0f}, {0.8f, 0.5f, 0.9f}, {0.5f, 0.8f, 0.9f}, {0.2f, 0.5f, 0.9f}};
  for (int k = 0; k < 4; ++k) {
    const std::size_t idx = t.index(k % 2, k / 2);
    for (int ch = 0; ch < 3; ++ch)
      EXPECT_NEAR(t.base_color[idx][ch], iec_decode(codes[k][ch] / 255.0) * files.base_color_factor[ch], 1e-6) << k;
    EXPECT_NEAR(t.roughness[idx], rough[k] * 0.9, 1e-4) << k;
    EXPECT_NEAR(t.metallic[idx], metal[k] * 0.5, 1e-4) << k;
    const glm::vec3 v = (2.0f * rgb[k] - 1.0f) * glm::vec3(2, 2, 1);
    const glm::vec3 n = t.normal[idx], want = v / std::sqrt(glm::dot(v, v));
    for (int ch = 0; ch < 3; ++ch) EXPECT_NEAR(n[ch], want[ch], 1e-4) << k;
  }
}

// Factors alone make a 1×1 material; a gray metallic-roughness map reads in G and B; straight
// alpha never darkens base color; a float base color is already linear.
TEST(MaterialLoader, FactorsGrayMapsAlphaAndLinearFloats) {
  const TempDir dir;
  MaterialFiles only_factors;
  only_factors.base_color_factor = {0.2f, 0.3f, 0.4f, 1.0f};
  only_factors.metallic_factor = 0.7f;
  only_factors.roughness_factor = 0.35f;
  const MaterialTexels f = load_material_texels(only_factors);
  ASSERT_EQ(f.size(), 1u);
  EXPECT_EQ(f.base_color[0], glm::vec3(0.2f, 0.3f, 0.4f));
  EXPECT_EQ(f.metallic[0], 0.7f);
  EXPECT_EQ(f.roughness[0], 0.35f);
  EXPECT_EQ(f.normal[0], glm::vec3(0, 0, 1));

  write_image(dir / "gray.png", image_of(1, 1, 1, {0.6f}), PixelFormat::uint16);
  write_image(dir / "rgba.png", image_of(1, 1, 4, {1.0f, 0.5f, 0.0f, 0.0f}), PixelFormat::uint8);
  MaterialFiles files;
  files.metallic_roughness = dir / "gray.png";
  files.base_color = dir / "rgba.png";
  const MaterialTexels g = load_material_texels(files);
  EXPECT_NEAR(g.roughness[0], 0.6, 1e-4);
  EXPECT_NEAR(g.metallic[0], 0.6, 1e-4);
  EXPECT_NEAR(g.base_color[0].r, 1.0, 1e-6);
  EXPECT_NEAR(g.base_color[0].g, iec_decode(128 / 255.0), 1e-6);

  write_image(dir / "linear.exr", image_of(1, 1, 3, {0.25f, 0.5f, 2.0f}), PixelFormat::float32);
  MaterialFiles exr;
  exr.base_color = dir / "linear.exr";
  EXPECT_EQ(load_material_texels(exr).base_color[0], glm::vec3(0.25f, 0.5f, 2.0f));
}

TEST(MaterialLoader, BadInputNamesTheFile) {
  const TempDir dir;
  write_image(dir / "a4.png", Image(4, 4, 3), PixelFormat::uint8);
  write_image(dir / "b8.png", Image(8, 8, 3), PixelFormat::uint8);
  write_image(dir / "gray_normal.png", Image(4, 4, 1), PixelFormat::uint8);
  {
    MaterialFiles f;
    f.base_color = dir / "a4.png";
    f.metallic_roughness = dir / "b8.png";
    expect_error_naming([&] { load_material_texels(f); }, {"b8.png", "a4.png", "differs"});
  }
  {
    MaterialFiles f;
    f.normal = dir / "gray_normal.png";
    expect_error_naming([&] { load_material_texels(f); }, {"gray_normal.png", "RGB"});
  }
  {
    MaterialFiles f;
    f.base_color = dir / "absent.png";
    expect_error_naming([&] { load_material_texels(f); }, {"absent.png"});
  }
  {
    std::ofstream(dir / "corrupt.png") << "\x89PNG\r\n\x1a\nthis is not a png";
    MaterialFiles f;
    f.metallic_roughness = dir / "corrupt.png";
    expect_error_naming([&] { load_material_texels(f); }, {"corrupt.png"});
  }
  {
    MaterialFiles f;
    f.metallic_factor = 1.5f;
    expect_error_naming([&] { load_material_texels(f); }, {"metallic factor"});
    f.metallic_factor = 1.0f;
    f.base_color_factor = {-1, 0, 0, 1};
    expect_error_naming([&] { load_material_texels(f); }, {"base color factor"});
  }
}

// The files decode in parallel, and a failure is the one a reading in order (base colour,
// metallic-roughness, normal) meets first, whichever decode fails first.
TEST(MaterialLoader, SeveralBadFilesReportTheFirstInReadingOrder) {
  const TempDir dir;
  std::ofstream(dir / "corrupt.png") << "\x89PNG\r\n\x1a\nthis is not a png";
  write_image(dir / "good.png", Image(4, 4, 3), PixelFormat::uint8);
  MaterialFiles f;
  f.base_color = dir / "absent_base.png";
  f.metallic_roughness = dir / "corrupt.png";
  f.normal = dir / "absent_normal.png";
  expect_error_naming([&] { load_material_texels(f); }, {"absent_base.png"});
  f.base_color = dir / "good.png";
  expect_error_naming([&] { load_material_texels(f); }, {"corrupt.png"});
  f.metallic_roughness = dir / "good.png";
  expect_error_naming([&] { load_material_texels(f); }, {"absent_normal.png"});
  f.normal = dir / "good.png";
  EXPECT_EQ(load_material_texels(f).width, 4);
}

// From memory (a .glb): the same decode with the names the caller gives.
TEST(MaterialLoader, DecodesImagesInMemoryWithTheirNames) {
  const Image base = image_of(1, 2, 3, {0.5f, 0.5f, 0.5f, 1.0f, 1.0f, 1.0f});
  const Image normal = image_of(2, 1, 3, {0.5f, 0.5f, 1.0f, 0.5f, 0.5f, 1.0f});
  MaterialImages in;
  in.base_color = &base;
  in.base_color_name = "scene.glb: images[0]";
  in.normal = &normal;
  in.normal_name = "scene.glb: images[1]";
  expect_error_naming([&] { decode_material_texels(in); }, {"scene.glb: images[1]", "scene.glb: images[0]"});
  in.normal = nullptr;
  const MaterialTexels t = decode_material_texels(in);
  EXPECT_NEAR(t.base_color[t.index(0, 0)].g, 0.214041, 1e-6);
  EXPECT_NEAR(t.base_color[t.index(0, 1)].g, 1.0, 1e-6);
}

}  // namespace
}  // namespace svbrdf
