// The procedural families against the physical ranges stated for them in textures/material_family.h
// (mean albedo, roughness histogram, slopes and bump geometry in mm), determinism, and bad input.
#include "textures/material_family.h"

#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cmath>
#include <map>

#include "base/error.h"

namespace svbrdf {
namespace {

float luminance(glm::vec3 c) { return 0.2126f * c.r + 0.7152f * c.g + 0.0722f * c.b; }

ProceduralMaterial make(const std::string& preset, const std::string& variant, int size = 256, std::uint64_t seed = 1,
                        double mm = 0.0) {
  return generate_material(MaterialRecipe{preset, variant, size, seed, mm});
}

template <class Pred>
double fraction(const MaterialTexels& t, Pred pred) {
  std::size_t n = 0;
  for (std::size_t k = 0; k < t.size(); ++k) n += pred(k) ? 1 : 0;
  return double(n) / double(t.size());
}

glm::dvec3 mean_color(const MaterialTexels& t) {
  glm::dvec3 s(0);
  for (const glm::vec3& c : t.base_color) s += glm::dvec3(c);
  return s / double(t.size());
}

double mean(const std::vector<float>& v) {
  double s = 0;
  for (float x : v) s += x;
  return s / double(v.size());
}

// Slope of the shading normal against the geometric surface, (−n.x/n.z, −n.y/n.z).
double rms_slope(const MaterialTexels& t) {
  double s2 = 0;
  for (const glm::vec3& n : t.normal) s2 += double(n.x * n.x + n.y * n.y) / double(n.z * n.z);
  return std::sqrt(s2 / double(t.size()));
}

double quantile(std::vector<float> v, double q) {
  std::sort(v.begin(), v.end());
  return v[std::size_t(q * double(v.size() - 1))];
}

// Roughness quantization of the stored 8-bit map: half a code.
constexpr float kCode8 = 0.5f / 255.0f;

TEST(Sandstone, MatteStrataInEachVariantsColor) {
  std::map<std::string, ProceduralMaterial> v;
  for (const char* name : {"red", "ochre", "buff"}) v.emplace(name, make("sandstone", name));
  for (const auto& [name, m] : v) {
    SCOPED_TRACE(name);
    const MaterialTexels& t = m.texels;
    for (float r : t.roughness) ASSERT_TRUE(r >= 0.8f - kCode8 && r <= 1.0f) << r;
    for (float x : t.metallic) ASSERT_EQ(x, 0.0f);
    // Bedding: strata run along rows, so row means vary much more than column means.
    std::vector<double> rows(t.height, 0.0), cols(t.width, 0.0);
    for (int j = 0; j < t.height; ++j)
      for (int i = 0; i < t.width; ++i) {
        const float y = luminance(t.base_color[t.index(i, j)]);
        rows[j] += y / t.width;
        cols[i] += y / t.height;
      }
    const auto variance = [](const std::vector<double>& x) {
      double m = 0, s = 0;
      for (double a : x) m += a / double(x.size());
      for (double a : x) s += (a - m) * (a - m) / double(x.size());
      return s;
    };
    EXPECT_GT(variance(rows), 3.0 * variance(cols));
    // Grain bumps: a rough surface, slopes of tenths.
    EXPECT_GT(rms_slope(t), 0.05);
    EXPECT_LT(rms_slope(t), 0.8);
  }
  const glm::dvec3 red = mean_color(v["red"].texels), ochre = mean_color(v["ochre"].texels), buff = mean_color(v["buff"].texels);
  // Linear R/G: hematite red is well above 2.5; goethite ochre, yellow-brown, below.
  EXPECT_GT(red.r / red.g, 2.5);
  EXPECT_LT(ochre.r / ochre.g, 2.3);
  EXPECT_TRUE(ochre.r > ochre.g && ochre.g > ochre.b);
  EXPECT_GT(ochre.g / ochre.b, 1.5);
  const auto y = [](glm::dvec3 c) { return 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b; };
  EXPECT_TRUE(y(red) > 0.08 && y(red) < 0.3) << y(red);
  EXPECT_TRUE(y(ochre) > 0.15 && y(ochre) < 0.45) << y(ochre);
  EXPECT_TRUE(y(buff) > 0.35 && y(buff) < 0.75) << y(buff);
  // The variants differ in roughness too, so one surface can mix them.
  EXPECT_GT(std::abs(mean(v["red"].texels.roughness) - mean(v["ochre"].texels.roughness)), 0.03);
  EXPECT_GT(mean(v["buff"].texels.roughness), mean(v["red"].texels.roughness));
}

TEST(Sandstone, MixedPutsRedAndOchreOnOneSurface) {
  const ProceduralMaterial m = make("sandstone", "mixed", 256, 1, 0.4);  // 102 mm: several regions
  const MaterialTexels& t = m.texels;
  const double red = fraction(t, [&](std::size_t k) { return t.base_color[k].r > 2.8f * t.base_color[k].g; });
  const double ochre = fraction(t, [&](std::size_t k) { return t.base_color[k].r < 2.3f * t.base_color[k].g; });
  EXPECT_GT(red, 0.1);
  EXPECT_GT(ochre, 0.1);
}

// Count local maxima that stand above the mean: one per bump.
double bumps_per_mm2(const ProceduralMaterial& m) {
  const MaterialTexels& t = m.texels;
  const std::vector<float>& h = m.height_mm;
  const double hm = mean(h);
  int count = 0;
  const int r = 5;  // 0.6 mm at 0.125 mm per texel: wider than the micro-texture, narrower than a bump
  for (int j = 0; j < t.height; ++j)
    for (int i = 0; i < t.width; ++i) {
      const float c = h[t.index(i, j)];
      if (c <= hm) continue;
      bool top = true;
      for (int dj = -r; dj <= r && top; ++dj)
        for (int di = -r; di <= r && top; ++di) {
          if (!di && !dj) continue;
          const int ii = (i + di + t.width) % t.width, jj = (j + dj + t.height) % t.height;
          top = h[t.index(ii, jj)] < c;
        }
      count += top ? 1 : 0;
    }
  return count / (m.side_mm() * m.side_mm());
}

TEST(PaintedWall, BumpsATenthOfAMillimeterHighTwoMillimetersApart) {
  for (const char* variant : {"white", "cream", "gray"}) {
    SCOPED_TRACE(variant);
    const ProceduralMaterial m = make("painted-wall", variant);
    const MaterialTexels& t = m.texels;
    // Bumps ~0.1 mm high: the height field's 5–95 % spread.
    const double spread = quantile(m.height_mm, 0.95) - quantile(m.height_mm, 0.05);
    EXPECT_TRUE(spread > 0.05 && spread < 0.2) << spread;
    // ~2 mm apart: about one bump per 4 mm².
    const double density = bumps_per_mm2(m);
    EXPECT_TRUE(density > 0.15 && density < 0.4) << density;
    // Slopes from 0.1 mm over ~1 mm: about a tenth.
    EXPECT_TRUE(rms_slope(t) > 0.03 && rms_slope(t) < 0.3) << rms_slope(t);
    // Roughness ~0.7, glossier on the bump tops than in the valleys.
    EXPECT_NEAR(mean(t.roughness), 0.7, 0.05);
    for (float r : t.roughness) ASSERT_TRUE(r > 0.6f && r < 0.8f) << r;
    const double h_top = quantile(m.height_mm, 0.9), h_low = quantile(m.height_mm, 0.1);
    double r_top = 0, r_low = 0;
    int n_top = 0, n_low = 0;
    for (std::size_t k = 0; k < t.size(); ++k) {
      if (m.height_mm[k] >= h_top) r_top += t.roughness[k], ++n_top;
      if (m.height_mm[k] <= h_low) r_low += t.roughness[k], ++n_low;
    }
    EXPECT_GT(r_low / n_low - r_top / n_top, 0.03);
    // Nearly constant albedo with slight variation.
    double ym = 0, y2 = 0;
    for (const glm::vec3& c : t.base_color) ym += luminance(c), y2 += double(luminance(c)) * luminance(c);
    ym /= double(t.size());
    const double ysd = std::sqrt(std::max(0.0, y2 / double(t.size()) - ym * ym));
    EXPECT_TRUE(ym > 0.45 && ym < 0.9) << ym;
    EXPECT_LT(ysd / ym, 0.05);
    EXPECT_GT(ysd / ym, 0.002);
    for (float x : t.metallic) ASSERT_EQ(x, 0.0f);
  }
}

TEST(PrintedPaper, OnlyAlbedoVaries) {
  for (const char* variant : {"text", "halftone"}) {
    SCOPED_TRACE(variant);
    const ProceduralMaterial m = make("printed-paper", variant);
    const MaterialTexels& t = m.texels;
    for (std::size_t k = 0; k < t.size(); ++k) {
      ASSERT_EQ(t.roughness[k], t.roughness[0]);
      ASSERT_EQ(t.metallic[k], 0.0f);
      ASSERT_GT(t.normal[k].z, 1.0f - 1e-6f);  // flat (16-bit code for 0.5 tilts by 2e-5 rad)
    }
    const double paper = fraction(t, [&](std::size_t k) { return luminance(t.base_color[k]) > 0.7f; });
    const double ink = fraction(t, [&](std::size_t k) { return luminance(t.base_color[k]) < 0.05f; });
    EXPECT_GT(paper, 0.25);
    EXPECT_GT(ink, std::string(variant) == "text" ? 0.02 : 0.1);
    EXPECT_GT(1.0 - paper - ink, 0.0);  // anti-aliased edges in between
  }
  // Halftone dots reproduce a picture whose tone averages one half.
  const MaterialTexels& h = make("printed-paper", "halftone").texels;
  const float white = luminance(h.base_color[0]) > 0.5f ? luminance(h.base_color[0]) : 0.88f;
  double coverage = 0;
  for (const glm::vec3& c : h.base_color) coverage += 1.0 - std::clamp(luminance(c) / white, 0.0f, 1.0f);
  coverage /= double(h.size());
  EXPECT_TRUE(coverage > 0.25 && coverage < 0.75) << coverage;
}

TEST(MetalTray, PolishedMetalWithRoughFingerprints) {
  for (const char* variant : {"steel", "silver", "brass"}) {
    SCOPED_TRACE(variant);
    const ProceduralMaterial m = make("metal-tray", variant);
    const MaterialTexels& t = m.texels;
    for (float x : t.metallic) ASSERT_EQ(x, 1.0f);
    const float q = 0.5f / 65535.0f;
    for (float r : t.roughness) ASSERT_TRUE(r >= 0.05f - q && r <= 0.6f + q) << r;
    const double polished = fraction(t, [&](std::size_t k) { return t.roughness[k] <= 0.1f + q; });
    const double print = fraction(t, [&](std::size_t k) { return t.roughness[k] >= 0.4f - q; });
    EXPECT_GT(polished, 0.5);
    EXPECT_GT(print, 0.02);
    EXPECT_LT(1.0 - polished - print, 0.25);  // ridge edges in between
    // The polish itself varies a little.
    std::vector<float> clean;
    for (std::size_t k = 0; k < t.size(); ++k)
      if (t.roughness[k] <= 0.1f) clean.push_back(t.roughness[k]);
    EXPECT_GT(quantile(clean, 0.95) - quantile(clean, 0.05), 0.01);
    // Residue tints the metal slightly: darker and warmer on the ridges.
    glm::dvec3 on(0), off(0);
    int n_on = 0, n_off = 0;
    for (std::size_t k = 0; k < t.size(); ++k) {
      if (t.roughness[k] >= 0.4f) on += glm::dvec3(t.base_color[k]), ++n_on;
      if (t.roughness[k] <= 0.1f) off += glm::dvec3(t.base_color[k]), ++n_off;
    }
    on /= double(n_on), off /= double(n_off);
    EXPECT_LT(on.g, off.g);
    EXPECT_GT(on.g, 0.8 * off.g);  // slight
    EXPECT_LT(on.b / on.r, off.b / off.r);
    // Residue ~1.5 µm proud: normals tilt by a degree or two at most.
    for (const glm::vec3& n : t.normal) ASSERT_GT(n.z, std::cos(3.0f * 3.14159f / 180.0f));
  }
}

// The prints sit around the rim: on an 82 mm tray, nothing rough farther than 22 mm from an edge.
TEST(MetalTray, FingerprintsAroundTheRim) {
  const ProceduralMaterial m = make("metal-tray", "steel", 256, 3, 0.32);
  const MaterialTexels& t = m.texels;
  int rough = 0;
  for (int j = 0; j < t.height; ++j)
    for (int i = 0; i < t.width; ++i) {
      if (t.roughness[t.index(i, j)] < 0.3f) continue;
      ++rough;
      const double x = (i + 0.5) * m.mm_per_texel, y = (j + 0.5) * m.mm_per_texel, side = m.side_mm();
      EXPECT_LT(std::min({x, y, side - x, side - y}), 22.0) << i << " " << j;
    }
  EXPECT_GT(rough, 100);
}

TEST(Granite, AnAggregateOfMineralsWithTheirOwnColorAndRoughness) {
  for (const char* variant : {"gray", "pink", "polished"}) {
    SCOPED_TRACE(variant);
    const ProceduralMaterial m = make("granite", variant);
    const MaterialTexels& t = m.texels;
    const auto y = [&](std::size_t k) { return luminance(t.base_color[k]); };
    // Three or more minerals: light feldspar, mid-gray quartz, dark hornblende and mica.
    const double light = fraction(t, [&](std::size_t k) { return y(k) > 0.3f; });
    const double mid = fraction(t, [&](std::size_t k) { return y(k) > 0.15f && y(k) < 0.3f; });
    const double dark = fraction(t, [&](std::size_t k) { return y(k) < 0.06f; });
    EXPECT_GT(light, 0.25);
    EXPECT_GT(mid, 0.12);
    EXPECT_GT(dark, 0.08);
    // Mica flecks: dark and the glossiest.
    const double mica = fraction(t, [&](std::size_t k) { return y(k) < 0.03f && t.roughness[k] < 0.25f; });
    EXPECT_GT(mica, 0.02);
    double r_light = 0, r_mid = 0, r_mica = 0;
    int n_light = 0, n_mid = 0, n_mica = 0;
    for (std::size_t k = 0; k < t.size(); ++k) {
      if (y(k) > 0.3f) r_light += t.roughness[k], ++n_light;
      if (y(k) > 0.15f && y(k) < 0.3f) r_mid += t.roughness[k], ++n_mid;
      if (y(k) < 0.03f && t.roughness[k] < 0.25f) r_mica += t.roughness[k], ++n_mica;
    }
    r_light /= n_light, r_mid /= n_mid, r_mica /= n_mica;
    EXPECT_LT(r_mica, r_mid);
    if (std::string(variant) == "polished") {
      for (float r : t.roughness) ASSERT_LT(r, 0.25f);
    } else {
      EXPECT_GT(r_light - r_mica, 0.25);  // matte feldspar, glossy mica
      EXPECT_GT(r_light - r_mid, 0.06);   // quartz glassier than feldspar
    }
    if (std::string(variant) == "pink") {
      glm::dvec3 c(0);
      for (std::size_t k = 0; k < t.size(); ++k)
        if (y(k) > 0.3f) c += glm::dvec3(t.base_color[k]);
      EXPECT_GT(c.r, 1.2 * c.g);
    }
    for (float x : t.metallic) ASSERT_EQ(x, 0.0f);
    // Plucked mica sits in tilted pits: some texels tilt by more than 2°, most do not.
    const double tilted = fraction(t, [&](std::size_t k) { return t.normal[k].z < std::cos(2.0f * 3.14159f / 180.0f); });
    EXPECT_TRUE(tilted > 0.005 && tilted < 0.3) << tilted;
  }
}

// Same recipe, same texels, at any thread count; another seed, other texels; textures tile.
TEST(MaterialFamily, DeterministicPerSeedAndTileable) {
  for (const MaterialPreset& p : material_presets()) {
    for (std::string_view variant : p.variants) {
      SCOPED_TRACE(std::string(p.name) + "/" + std::string(variant));
      const ProceduralMaterial a = make(std::string(p.name), std::string(variant), 64, 7);
      ProceduralMaterial b;
      tbb::task_arena one(1);
      one.execute([&] { b = make(std::string(p.name), std::string(variant), 64, 7); });
      EXPECT_EQ(a.base_color.pixels, b.base_color.pixels);
      EXPECT_EQ(a.metallic_roughness.pixels, b.metallic_roughness.pixels);
      EXPECT_EQ(a.normal.pixels, b.normal.pixels);
      EXPECT_EQ(a.height_mm, b.height_mm);
      const ProceduralMaterial c = make(std::string(p.name), std::string(variant), 64, 8);
      EXPECT_NE(a.base_color.pixels, c.base_color.pixels);
    }
  }
  // Tiling: across the wrap the height field changes no more than between the neighbouring
  // columns (or rows) just inside either edge.
  for (const MaterialPreset& p : material_presets()) {
    if (p.name == "printed-paper") continue;  // flat
    SCOPED_TRACE(std::string(p.name));
    const ProceduralMaterial m = make(std::string(p.name), "", 128, 2);
    const int n = m.texels.width;
    const auto step = [&](bool along_rows, int a, int b) {
      double s = 0;
      for (int k = 0; k < n; ++k)
        s += along_rows ? std::abs(m.height_mm[k * n + a] - m.height_mm[k * n + b]) : std::abs(m.height_mm[a * n + k] - m.height_mm[b * n + k]);
      return s;
    };
    for (bool along_rows : {true, false}) {
      const double seam = step(along_rows, n - 1, 0);
      const double inside = std::max(step(along_rows, 0, 1), step(along_rows, n - 2, n - 1));
      EXPECT_LT(seam, 2.0 * inside + 1e-9) << (along_rows ? "columns" : "rows");
    }
  }
}

template <class Fn>
void expect_bad_input(Fn fn, const std::string& needle) {
  try {
    fn();
    ADD_FAILURE() << "no error; expected one naming " << needle;
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
    EXPECT_EQ(e.exit_code(), 2);
  }
}

TEST(MaterialFamily, BadRecipesAreBadInput) {
  expect_bad_input([] { make("marble", ""); }, "marble");
  expect_bad_input([] { make("marble", ""); }, "granite");  // the message lists the known presets
  expect_bad_input([] { make("granite", "blue"); }, "blue");
  expect_bad_input([] { make("granite", "", 100); }, "power of two");
  expect_bad_input([] { make("granite", "", 0); }, "power of two");
  expect_bad_input([] { make("granite", "", 1 << 15); }, "power of two");
  expect_bad_input([] { make("granite", "", 64, 1, -0.1); }, "mm per texel");
  EXPECT_EQ(find_material_preset("metal-tray").variants.front(), "steel");
  EXPECT_EQ(make("printed-paper", "halftone", 8).mm_per_texel, 0.05);
  EXPECT_EQ(make("printed-paper", "", 8).variant, "text");
}

}  // namespace
}  // namespace svbrdf
