// The LOD comparison's ground truth and metrics, checked against what is known independently of the
// renderer's MIP filters:
//  - the metrics on images with closed-form answers;
//  - the level0 ground truth's mean radiance at k ≥ 16 (where the image spans whole texture
//    repeats) equals E · mean over the texture's level-0 texels of f_x(wi, wo)·max(0, n_x·wi), the
//    spec's f_eff (brdf-mip.md) evaluated with the glTF BRDF from the baked files: the scenes, their
//    lights and cameras, and the renderer's level-0 shading agree with the spec;
//  - the noise floor falls as 1/spp (two seeds give independent estimates).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

#include "appearance/frame.h"
#include "base/error.h"
#include "appearance/gltf.h"
#include "lod/comparison.h"
#include "lod/metrics.h"
#include "scenes/lod_scenes.h"
#include "textures/material_loader.h"
#include "tests/common/test_paths.h"

namespace svbrdf {
namespace {

namespace fs = std::filesystem;
const fs::path kManifest = fs::path(SVBRDF_BINARY_DIR) / "scenes" / "lod" / "manifest.json";

Image constant(int w, int h, float r, float g, float b) {
  Image im(w, h, 3);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) im.at(x, y, 0) = r, im.at(x, y, 1) = g, im.at(x, y, 2) = b;
  return im;
}

TEST(LodMetrics, ClosedFormCases) {
  const Image R = constant(4, 4, 0.2f, 0.4f, 0.6f);
  const std::vector<std::uint8_t> all(16, 1);
  LodMetrics same = compare_images(R, R, all);
  EXPECT_EQ(same.rel_mse, 0.0);
  EXPECT_EQ(same.flux_bias, 0.0);
  EXPECT_EQ(same.peak_ratio, 1.0);
  const Image X = constant(4, 4, 0.4f, 0.8f, 1.2f);  // twice R: (X − R)² = R², flux ×2, peak ×2
  const LodMetrics twice = compare_images(X, R, all);
  EXPECT_NEAR(twice.rel_mse, 1.0, 1e-6);
  EXPECT_NEAR(twice.flux_bias, 1.0, 1e-6);
  EXPECT_NEAR(twice.peak_ratio, 2.0, 1e-6);
  // One bright pixel in X: the peak ratio sees it, the mask can hide it.
  Image Y = R;
  Y.at(1, 2, 0) = Y.at(1, 2, 1) = Y.at(1, 2, 2) = 4.0f;
  const double peak_r = 0.2126 * 0.2 + 0.7152 * 0.4 + 0.0722 * 0.6;
  EXPECT_NEAR(compare_images(Y, R, all).peak_ratio, 4.0 / peak_r, 1e-5);
  std::vector<std::uint8_t> mask = all;
  mask[2 * 4 + 1] = 0;
  EXPECT_EQ(compare_images(Y, R, mask).rel_mse, 0.0);
  // The mask comes from depth.
  Image depth(2, 1, 1);
  depth.at(0, 0, 0) = 0.0f, depth.at(1, 0, 0) = 3.0f;
  EXPECT_EQ(object_mask(depth), (std::vector<std::uint8_t>{0, 1}));
  EXPECT_THROW(compare_images(R, R, std::vector<std::uint8_t>(16, 0)), Error);
}

// E · mean over the level-0 texels of f_x(wi, wo)·max(0, n_x·wi), the spec's f_eff·wi.z·E.
glm::dvec3 expected_radiance(const MaterialTexels& t, const glm::vec3& wi, const glm::vec3& wo, double E) {
  glm::dvec3 sum(0.0);
  for (std::size_t x = 0; x < t.size(); ++x) {
    const glm::vec3 n = t.normal[x];
    if (glm::dot(n, wi) <= 0 || glm::dot(n, wo) <= 0) continue;
    const Frame f = Frame::from_normal(n);
    const GltfParams p{t.base_color[x], t.metallic[x], t.roughness[x]};
    sum += glm::dvec3(gltf_eval(p, f.to_local(wi), f.to_local(wo))) * double(glm::dot(n, wi));
  }
  return sum * E / double(t.size());
}

TEST(LodGroundTruth, MeanRadianceIsTheTexturesMeanBrdf) {
  const LodManifest m = read_lod_manifest(kManifest);
  LodOptions o;
  o.spp = 64;
  o.filters.clear();
  o.min_distance = 16;  // the image spans 3 whole texture repeats from 16× on (48 px × 16 texels = 3 × 256)
  o.views = {"head-on"};
  o.lights = {"sun-0", "sun-45", "sun-75"};
  int checked = 0;
  for (const LodCase& c : m.cases) {
    // Rough families: f hardly changes over the ±5° of view directions in the image.
    if (c.kind != "family" || c.glossy) continue;
    o.cases = {c.name};
    const LodResults r = run_lod_comparison(m, o);
    MaterialFiles files;
    const fs::path tex = c.gltf.parent_path() / "textures";
    files.base_color = tex / (c.name + "_base_color.png");
    files.metallic_roughness = tex / (c.name + "_metallic_roughness.png");
    files.normal = tex / (c.name + "_normal.png");
    const MaterialTexels texels = load_material_texels(files);
    ASSERT_EQ(texels.width * (m.image_size * 16) % texels.width, 0);
    for (const LodShot& s : r.shots) {
      const double theta = m.light(s.light).incidence_deg * std::numbers::pi / 180;
      const glm::vec3 wi(float(std::sin(theta)), 0.0f, float(std::cos(theta)));
      const glm::dvec3 want = expected_radiance(texels, wi, {0, 0, 1}, 1.0);
      glm::dvec3 got(0.0);
      for (int y = 0; y < s.truth.height; ++y)
        for (int x = 0; x < s.truth.width; ++x)
          for (int ch = 0; ch < 3; ++ch) got[ch] += s.truth.at(x, y, ch);
      got /= double(s.truth.width * s.truth.height);
      for (int ch = 0; ch < 3; ++ch)
        EXPECT_NEAR(got[ch] / want[ch], 1.0, 0.01) << c.name << " " << s.light << " " << s.multiple << "x channel " << ch;
      ++checked;
    }
  }
  // Three rough families, three suns, six distances: to 16384×, where the uv reach ±1690 repeats.
  EXPECT_EQ(checked, 3 * 3 * 6);
}

TEST(LodGroundTruth, NoiseFloorFallsAsOneOverSpp) {
  const LodManifest m = read_lod_manifest(kManifest);
  LodOptions o;
  o.filters.clear();
  o.keep_images = false;
  o.min_distance = 64;
  o.lights = {"sun-45", "sky"};
  o.views = {"head-on"};
  o.cases = {"painted-wall-white", "metal-tray-steel"};
  o.spp = 32;
  const LodResults a = run_lod_comparison(m, o);
  o.spp = 128;
  const LodResults b = run_lod_comparison(m, o);
  ASSERT_EQ(a.shots.size(), b.shots.size());
  ASSERT_FALSE(a.shots.empty());
  for (std::size_t i = 0; i < a.shots.size(); ++i) {
    const double ratio = b.shots[i].floor.rel_mse / a.shots[i].floor.rel_mse;
    // Four times the samples: a quarter of the variance (±40 % for the estimate's own noise).
    EXPECT_NEAR(ratio, 0.25, 0.1) << a.shots[i].case_name << " " << a.shots[i].light << " " << a.shots[i].multiple;
  }
}

}  // namespace
}  // namespace svbrdf
