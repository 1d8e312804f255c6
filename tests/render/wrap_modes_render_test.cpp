// The glTF sample TextureSettingsTest under every texture filter: its cells read one texture with each
// wrap mode per axis (repeat, clamp-to-edge, mirrored repeat along s and along t) over uv ranges that
// reach past [0, 1], and its screenshot shows each as level0 renders it (the nearest texel under the
// sampler's wrap modes, textures/sampler.h). Every MIP filter must render each cell as level0 does: a
// clamped axis must not average in the texture's opposite edge at a coarse level (mip_lookup.h).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "gltf/scene_reader.h"
#include "gltf_samples.h"
#include "render/render_setup.h"
#include "render/renderer.h"
#include "render_test_scenes.h"

namespace svbrdf {
namespace {

// The cells' quads (the file's meshes 0–3 and 5–8), in the board's plane z = 0 after its node's
// rotation: columns "Test" x ∈ [0.005, 0.905] and "Sample pass" x ∈ [2.151, 3.051], rows by mesh.
struct Cell {
  const char* name;
  float y0, y1;
};
constexpr Cell kRows[] = {{"texture mirror t", -5.165f, -4.265f}, {"texture mirror s", -4.128f, -3.228f},
                          {"texture repeat t", -3.091f, -2.191f}, {"texture repeat s", -2.054f, -1.154f},
                          {"texture clamp t", -1.020f, -0.120f},  {"texture clamp s", 0.017f, 0.917f},
                          {"double-sided", 1.070f, 1.970f},       {"single-sided", 2.095f, 2.995f}};
constexpr float kColumns[2] = {0.005f, 2.151f};
constexpr float kCellSize = 0.9f;

// An orthographic view of the two columns, 0.05 m a pixel: 18 pixels a cell.
constexpr float kX0 = -0.05f, kY0 = -5.25f, kPixel = 0.05f;
constexpr int kW = 64, kH = 168, kSpp = 16;

TEST(WrapModesRender, EveryFilterRendersTextureSettingsTestAsLevel0) {
  const auto file = test::samples_dir() / "TextureSettingsTest/glTF/TextureSettingsTest.gltf";
  if (!std::filesystem::exists(file)) GTEST_SKIP() << "no glTF samples at " << test::samples_dir() << " (../shared absent)";
  Scene scene = load_gltf(file);
  const glm::vec3 centre(kX0 + 0.5f * kW * kPixel, kY0 + 0.5f * kH * kPixel, 0.0f);
  scene.cameras.insert(scene.cameras.begin(), test::ortho_camera(centre + glm::vec3(0, 0, 5), centre, 0.5f * kH * kPixel));
  SceneSetup setup;
  setup.width = kW, setup.height = kH;
  const PreparedScene prepared(std::move(scene), setup);
  auto render_with = [&](TextureFilter f, std::uint64_t seed) {
    RenderOptions o;
    o.spp = kSpp;
    o.seed = seed;
    o.aovs = false;
    o.integrator.filter = f;
    return render(prepared.world(), o).radiance();
  };
  const Image level0 = render_with(TextureFilter::level0, 1), level0_again = render_with(TextureFilter::level0, 2);

  // A cell's inner square (2 pixels in from its edges, clear of the quad's own antialiased border).
  struct Region {
    int x0, y0, x1, y1;
  };
  auto inner = [](int column, const Cell& row) {
    const int x0 = int(std::ceil((kColumns[column] - kX0) / kPixel)) + 2;
    // Image rows grow downward, world y upward.
    const int y0 = int(std::ceil((kY0 + kH * kPixel - row.y1) / kPixel)) + 2;
    const int n = int(kCellSize / kPixel) - 5;
    return Region{x0, y0, x0 + n, y0 + n};
  };
  auto mean = [](const Image& im, const Region& r, int c) {
    double s = 0;
    for (int y = r.y0; y < r.y1; ++y)
      for (int x = r.x0; x < r.x1; ++x) s += im.at(x, y, c);
    return s / double((r.x1 - r.x0) * (r.y1 - r.y0));
  };
  // The noise of a cell's mean: two level0 renders of other seeds differ by √2 σ, RMS over the cells.
  double pair = 0;
  int count = 0;
  for (int column = 0; column < 2; ++column)
    for (const Cell& row : kRows)
      for (int c = 0; c < 3; ++c, ++count) pair += std::pow(mean(level0, inner(column, row), c) - mean(level0_again, inner(column, row), c), 2);
  const double sigma = std::sqrt(pair / count / 2.0);
  EXPECT_LT(sigma, 0.01) << "the cells' means are noisier than this test's bounds allow for";

  // A filter moves into a region only what differs across its edge, from within the filter's reach h:
  // at most contrast × perimeter × h / area, the contrast being the spread of level0's values in the
  // band of width 2h around the region's edge. Each sample's footprint is 1/√spp of a pixel (a quarter)
  // and the trilinear kernel reaches two texels of its upper level, at most twice the footprint: h = ½.
  constexpr double kReach = 0.5;
  auto contrast = [&](const Region& r, int c) {
    float lo = 1e30f, hi = -1e30f;
    for (int y = r.y0 - 1; y < r.y1 + 1; ++y)
      for (int x = r.x0 - 1; x < r.x1 + 1; ++x)
        if (x < r.x0 + 1 || x >= r.x1 - 1 || y < r.y0 + 1 || y >= r.y1 - 1)
          lo = std::min(lo, level0.at(x, y, c)), hi = std::max(hi, level0.at(x, y, c));
    return double(hi - lo);
  };
  for (TextureFilter f : {TextureFilter::param, TextureFilter::toksvig, TextureFilter::vmf, TextureFilter::brdf}) {
    const Image im = render_with(f, 1);
    for (int column = 0; column < 2; ++column)
      for (const Cell& row : kRows) {
        const Region r = inner(column, row);
        const double side = r.x1 - r.x0, spill = 4.0 * side * kReach / (side * side);
        for (int c = 0; c < 3; ++c) {
          const double bound = 6.0 * std::sqrt(2.0) * sigma + contrast(r, c) * spill;
          EXPECT_NEAR(mean(im, r, c), mean(level0, r, c), bound)
              << filter_name(f) << ": " << row.name << (column ? " (sample pass)" : " (test)") << ", channel " << "RGB"[c];
        }
      }
  }
}

}  // namespace
}  // namespace svbrdf
