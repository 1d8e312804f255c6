// The coarse texels' radial correction (mip/radial_correction.h): what it carries up the pyramid is
// the exact area-weighted mean of the first corrected level's union profile (a linear identity,
// computed here from that level's children directly), it is 1 where the lobes are exact, and its
// lookup returns the stored ratios at the nodes.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include <glm/geometric.hpp>

#include "mip/mip_data.h"
#include "mip/pyramid_shape.h"
#include "mip/radial_correction.h"
#include "tests/mip/synthetic_materials.h"
#include "textures/material_family.h"

namespace svbrdf {
namespace {

constexpr double kPi = 3.14159265358979323846;

// Σ over a level's texels of area share × its lobes' profile × ratio(texel, node).
template <class Ratio>
RadialProfile area_weighted_profile(const MipData& mip, int level, Ratio ratio) {
  const BrdfPyramid& p = mip.brdf;
  const Extent e = p.extent(level), e0 = p.level0();
  RadialProfile out{};
  for (int j = 0; j < e.height; ++j)
    for (int i = 0; i < e.width; ++i) {
      const double share = double(level0_span(e0.width, level, i).size()) * level0_span(e0.height, level, j).size() /
                           (double(e0.width) * e0.height);
      RadialProfile own{};
      add_to_profile(p.radial_grid(), p.texel(level, i, j), own);
      for (std::size_t r = 0; r < RadialGrid::kNodes; ++r) out[r] += share * ratio(i, j, r) * own[r];
    }
  return out;
}

// What a level reflects at the nodes after correction.
RadialProfile corrected_level_profile(const MipData& mip, int level) {
  return area_weighted_profile(mip, level, [&](int i, int j, std::size_t r) {
    const RadialCorrection* c = mip.brdf.correction(level, i, j);
    EXPECT_NE(c, nullptr);
    return c ? double(c->ratio[r]) : 0.0;
  });
}

// The level below the first corrected one, uncorrected: the union the correction starts from.
RadialProfile union_profile(const MipData& mip) {
  return area_weighted_profile(mip, kFirstCorrectedLevel - 1, [](int, int, std::size_t) { return 1.0; });
}

TEST(RadialCorrection, EveryCorrectedLevelReflectsItsUnionsProfile) {
  struct Case {
    const char* name;
    MaterialTexels m;
  };
  const Case cases[] = {{"granite 64x64", synthetic::granite(64)}, {"tray 64x64", synthetic::tray(64)},
                        {"sandstone 72x40", synthetic::sandstone(72)}};
  for (const Case& c : cases) {
    MaterialTexels m = c.m;
    if (std::string(c.name).find("72x40") != std::string::npos) {
      // A non-power-of-two, non-square level 0: the last texel of a level takes the remainder.
      MaterialTexels cut(72, 40);
      for (int y = 0; y < 40; ++y)
        for (int x = 0; x < 72; ++x) {
          const std::size_t s = static_cast<std::size_t>(y) * 72 + x, d = s;
          cut.base_color[d] = m.base_color[s], cut.metallic[d] = m.metallic[s], cut.roughness[d] = m.roughness[s],
          cut.normal[d] = m.normal[s];
        }
      m = cut;
    }
    const MipData mip = build_mip(m, {});
    ASSERT_GT(mip.levels(), kFirstCorrectedLevel) << c.name;
    const RadialProfile want = union_profile(mip);
    for (int level = kFirstCorrectedLevel; level < mip.levels(); ++level) {
      const RadialProfile got = corrected_level_profile(mip, level);
      // Nodes beyond kGateFromDeg are gated per texel (correction_gate): only the inner ones are exact.
      for (std::size_t r = 0; r < RadialGrid::kNodes && mip.brdf.radial_grid().theta[r] <= RadialGrid::kGateFromDeg * kPi / 180; ++r)
        // The ratios are half floats: 2⁻¹¹ relative each.
        EXPECT_NEAR(got[r], want[r], 1e-3 * want[r]) << c.name << ", level " << level << ", node " << r;
    }
    // Below the first corrected level there is none.
    EXPECT_EQ(mip.brdf.correction(kFirstCorrectedLevel - 1, 0, 0), nullptr);
  }
}

// A level's first azimuthal harmonics ⟨·cos φ⟩, ⟨·sin φ⟩ at the nodes within kGateFromDeg, with each
// texel's ratio applied (R is radial: it scales a node's harmonics as it scales its profile), and the
// same of the union the correction starts from, uncorrected.
std::vector<glm::dvec2> first_harmonics(const MipData& mip, int level, bool corrected) {
  const BrdfPyramid& p = mip.brdf;
  const RadialGrid& g = p.radial_grid();
  const Extent e = p.extent(level), e0 = p.level0();
  std::vector<glm::dvec2> out(RadialGrid::kNodes, glm::dvec2(0.0));
  for (int j = 0; j < e.height; ++j)
    for (int i = 0; i < e.width; ++i) {
      const double share = double(level0_span(e0.width, level, i).size()) * level0_span(e0.height, level, j).size() /
                           (double(e0.width) * e0.height);
      RadialProfile own{};
      AzimuthalHarmonics h{};
      add_to_profile(g, p.texel(level, i, j), own, &h);
      const RadialCorrection* c = corrected ? p.correction(level, i, j) : nullptr;
      for (std::size_t r = 0; r < RadialGrid::kNodes; ++r)
        out[r] += share * (c ? double(c->ratio[r]) : 1.0) * glm::dvec2(h[r][0], h[r][1]);
    }
  return out;
}

// The re-centring (radial_correction.h): a coarse level's highlight keeps the centre of the union it was
// reduced from. The mismatch of a level's first azimuthal harmonics (a shift) with the union's, over the
// nodes within kGateFromDeg weighted by their rings' areas, relative to the profile's, is the
// re-centring's own least-squares objective summed over the level's texels.
double centre_mismatch(const MipData& mip, int level) {
  const RadialGrid& g = mip.brdf.radial_grid();
  const std::vector<glm::dvec2> want = first_harmonics(mip, kFirstCorrectedLevel - 1, false);
  const std::vector<glm::dvec2> got = first_harmonics(mip, level, true);
  const RadialProfile profile = union_profile(mip);
  double num = 0, den = 0;
  for (std::size_t r = 1; r + 1 < RadialGrid::kNodes && g.theta[r] <= RadialGrid::kGateFromDeg * kPi / 180; ++r) {
    const double area = g.theta[r] * 0.5 * (g.theta[r + 1] - g.theta[r - 1]);
    num += area * glm::dot(got[r] - want[r], got[r] - want[r]);
    den += area * profile[r] * profile[r];
  }
  return std::sqrt(num / den);
}

TEST(RadialCorrection, EveryCorrectedLevelKeepsItsUnionsHighlightCentre) {
  const MaterialTexels tray = generate_material(MaterialRecipe{"metal-tray", "steel", 256, 24}).texels;
  BrdfBuildOptions off;
  off.recentre = false;
  const MipData with = build_mip(tray, {}), without = build_mip(tray, off);
  ASSERT_GT(with.levels(), kFirstCorrectedLevel + 2);
  // The polished tray at 256² (α ≈ 0.005): without the re-centring its levels miss the union's centre by
  // 0.15–0.65 % of the profile; with it, each level by less than 0.5 % and by at most 70 % of that (the
  // tilt's bound of 2.5e-4 rad holds levels 4 and 5 to about two thirds; levels 7 and 8 come to 25–40 %).
  for (int level = kFirstCorrectedLevel; level < with.levels(); ++level) {
    const double w = centre_mismatch(with, level), wo = centre_mismatch(without, level);
    EXPECT_LT(w, 0.005) << "level " << level << ": " << w << " against " << wo;
    EXPECT_LT(w, 0.7 * wo) << "level " << level << ": " << w << " against " << wo;
  }
}

// recentring_tilt finds a known shift: the truth is the lobes tilted by δ₀.
TEST(RadialCorrection, RecentringFindsAKnownShift) {
  const RadialGrid g = RadialGrid::for_sharpest(2.5e-5);
  Lobe sharp, rough;
  sharp.weight = 0.6f, sharp.f0 = glm::vec3(0.9f), sharp.alpha2 = 2.5e-5f;
  sharp.normal = glm::normalize(glm::vec3(0.002f, 0.001f, 1.0f));
  rough.weight = 0.4f, rough.f0 = glm::vec3(0.5f), rough.alpha2 = 0.01f;
  rough.normal = glm::normalize(glm::vec3(-0.01f, 0.0f, 1.0f));
  const std::vector<Lobe> lobes{sharp, rough};
  const auto shifted = [&](glm::dvec2 d) {
    std::vector<Lobe> out = lobes;
    for (Lobe& l : out) l.normal = glm::vec3(glm::normalize(glm::dvec3(l.normal) + glm::dvec3(d, 0.0)));
    return out;
  };
  for (const glm::dvec2 d0 : {glm::dvec2(1.5e-5, -1e-5), glm::dvec2(-1e-4, 0.5e-4), glm::dvec2(0.0)}) {
    RadialProfile truth{};
    AzimuthalHarmonics truth_h{};
    add_to_profile(g, shifted(d0), truth, &truth_h);
    const glm::dvec2 d = recentring_tilt(g, truth_h, lobes);
    EXPECT_LT(glm::length(d - d0), 0.05 * glm::length(d0) + 1e-8) << d0.x << " " << d0.y << ": " << d.x << " " << d.y;
  }
  // A shift past the tilt's bound (2.5e-4 rad, or a tenth of the grid's inner node: radial_correction.h)
  // but still small against the sharp lobe (a tenth of its α) is followed in its direction to the bound.
  // (Far larger shifts leave the linearization: at 0.05 rad the fit points the other way.)
  RadialProfile truth{};
  AzimuthalHarmonics truth_h{};
  add_to_profile(g, shifted(glm::dvec2(5e-4, 0.0)), truth, &truth_h);
  const glm::dvec2 d = recentring_tilt(g, truth_h, lobes);
  EXPECT_NEAR(glm::length(d), std::min(2.5e-4, 0.1 * double(g.inner)), 1e-12);
  EXPECT_GT(d.x, 0.99 * glm::length(d));
}

TEST(RadialCorrection, IsOneWhereTheLobesAreExact) {
  // Every texel alike: each coarse texel's lobes are its union exactly.
  MaterialTexels m(64, 64);
  for (std::size_t k = 0; k < m.size(); ++k) {
    m.base_color[k] = glm::vec3(0.9f, 0.8f, 0.7f);
    m.metallic[k] = 1.0f;
    m.roughness[k] = 0.2f;
    m.normal[k] = glm::normalize(glm::vec3(0.1f, -0.05f, 1.0f));
  }
  const MipData mip = build_mip(m, {});
  for (int level = kFirstCorrectedLevel; level < mip.levels(); ++level) {
    const RadialCorrection* c = mip.brdf.correction(level, 0, 0);
    ASSERT_NE(c, nullptr);
    for (float r : c->ratio) EXPECT_NEAR(r, 1.0f, 1e-3f) << "level " << level;
  }
}

TEST(RadialCorrection, TheGateIsOpenForEqualShapesAndClosedFromFifteenPercent) {
  const std::array<double, 4> shape{0.3, -0.1, 0.2, 0.05};
  EXPECT_EQ(correction_gate(shape, shape), 1.0);
  // The ratio's first-order azimuthal amplitude 2 Σ |tₙ − oₙ|: 0.1 halfway, 0.15 closed.
  std::array<double, 4> off = shape;
  off[2] += 0.05;
  EXPECT_NEAR(correction_gate(off, shape), 0.5, 1e-12);
  off[0] += 0.025;
  EXPECT_EQ(correction_gate(off, shape), 0.0);
}

TEST(RadialCorrection, TheGateClosesOutwardOnly) {
  const RadialGrid g = RadialGrid::for_sharpest(1e-4);
  Lobe l;
  l.weight = 1.0f, l.f0 = glm::vec3(0.9f), l.alpha2 = 0.04f;
  l.normal = glm::normalize(glm::vec3(0.2f, 0.1f, 1.0f));
  const std::vector<Lobe> lobes{l};
  RadialProfile own{};
  AzimuthalHarmonics own_h{};
  add_to_profile(g, lobes, own, &own_h);
  // The truth 10 % brighter at every node with the lobes' azimuthal shape: R = 1.1 everywhere.
  RadialProfile truth = own;
  AzimuthalHarmonics truth_h = own_h;
  for (std::size_t r = 0; r < RadialGrid::kNodes; ++r) {
    truth[r] *= 1.1;
    for (double& x : truth_h[r]) x *= 1.1;
  }
  const RadialCorrection even = correction_to(g, truth, truth_h, lobes);
  for (std::size_t r = 0; r < RadialGrid::kNodes; ++r) EXPECT_NEAR(even.ratio[r], 1.1f, 1e-3f) << "node " << r;
  // The first gated node's shape off by 0.2 in cos 2φ: no correction there or beyond, all of it before.
  std::size_t first = 0;
  while (g.theta[first] <= RadialGrid::kGateFromDeg * kPi / 180) ++first;
  ASSERT_LT(first + 1, RadialGrid::kNodes);
  truth_h[first][2] += 0.1 * truth[first];
  const RadialCorrection cut = correction_to(g, truth, truth_h, lobes);
  for (std::size_t r = 0; r < RadialGrid::kNodes; ++r)
    EXPECT_NEAR(cut.ratio[r], r < first ? 1.1f : 1.0f, 1e-3f) << "node " << r;
}

TEST(RadialCorrection, LookupReturnsTheRatiosAtTheNodesAndFadesToOneBeyond) {
  const RadialGrid g = RadialGrid::for_sharpest(1e-4);
  RadialCorrection c;
  for (std::size_t r = 0; r < RadialGrid::kNodes; ++r) c.ratio[r] = 1.0f + 0.01f * static_cast<float>(r * r);
  for (std::size_t r = 0; r < RadialGrid::kNodes; ++r) {
    const double t = g.theta[r];
    const glm::vec3 h(static_cast<float>(std::sin(t)), 0.0f, static_cast<float>(std::cos(t)));
    EXPECT_NEAR(correction_at(c, g, h), c.ratio[r], 2e-4f) << "node " << r;
  }
  // Between two nodes: between their ratios.
  const double mid = std::sqrt(g.theta[4] * g.theta[5]);
  const float v = correction_at(c, g, glm::vec3(static_cast<float>(std::sin(mid)), 0.0f, static_cast<float>(std::cos(mid))));
  EXPECT_GT(v, c.ratio[4]);
  EXPECT_LT(v, c.ratio[5]);
  // Past the last node R goes to 1 at kFadeEndDeg, linearly in ln(1 − cos θ): halfway there in ln u,
  // halfway between the last ratio and 1; 1 from there on.
  const auto at_deg = [&](double deg) {
    const double t = deg * 3.14159265358979 / 180;
    return correction_at(c, g, glm::vec3(static_cast<float>(std::sin(t)), 0.0f, static_cast<float>(std::cos(t))));
  };
  const double u_last = 1 - std::cos(RadialGrid::kOuterDeg * 3.14159265358979 / 180);
  const double u_end = 1 - std::cos((RadialGrid::kFadePerOuter * RadialGrid::kOuterDeg) * 3.14159265358979 / 180);
  const double half_deg = std::acos(1 - std::sqrt(u_last * u_end)) * 180 / 3.14159265358979;
  const float last = c.ratio[RadialGrid::kNodes - 1];
  EXPECT_NEAR(at_deg(half_deg), 0.5f * (last + 1.0f), 1e-4f);
  EXPECT_FLOAT_EQ(at_deg((RadialGrid::kFadePerOuter * RadialGrid::kOuterDeg) + 0.5), 1.0f);
  EXPECT_FLOAT_EQ(at_deg(60.0), 1.0f);
}

TEST(RadialCorrection, NoneWhenTurnedOff) {
  BrdfBuildOptions o;
  o.radial_correction = false;
  const MipData mip = build_mip(synthetic::tray(64), o);
  EXPECT_EQ(mip.brdf.correction(kFirstCorrectedLevel, 0, 0), nullptr);
}

}  // namespace
}  // namespace svbrdf
