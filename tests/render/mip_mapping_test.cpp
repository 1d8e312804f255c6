// Textures that one material maps differently — another KHR_texture_transform, another size, another
// wrap mode — resampled onto one texel grid (render/texel_grid.h): each such material takes part in
// the MIP filters with no warning, and renders as the same material rebaked by hand with every texture
// on one mapping (index arithmetic written here, not the resampler), the equivalent scene; the grid's
// level-0 texels are each texture's nearest texel as textures/sampler.h reads it; a grid that cannot
// hold the textures exactly leaves level-0 hits to the textures; the mappings no grid serves are named.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>

#include "appearance/rng.h"
#include "mip_quad.h"
#include "render/uv_relation.h"
#include "textures/sampler.h"

namespace svbrdf {
namespace {

using namespace mip_quad;

enum class Slot { base, mr, normal };

// A w×h image of one glTF slot whose texels are the kinds A–E drawn at random from `seed`.
Image slot_image(int w, int h, std::uint64_t seed, Slot slot) {
  const TexelSpec kinds[5] = {kA, kB, kC, kD, kE};
  Rng rng(seed, 7);
  Image im(w, h, 3);
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i) {
      const TexelSpec& t = kinds[rng.next_u32() % 5];
      const glm::vec3 v = slot == Slot::base ? t.srgb
                          : slot == Slot::mr ? glm::vec3(1.0f, t.roughness, t.metallic)
                                             : 0.5f * t.normal + 0.5f;
      for (int c = 0; c < 3; ++c) im.at(i, j, c) = v[c];
    }
  return im;
}

// The w×h image whose texel (i, j) is `im`'s texel at(i, j): a texture rebaked onto another grid by hand.
Image rebaked(const Image& im, int w, int h, const std::function<glm::ivec2(int, int)>& at) {
  Image out(w, h, im.channels);
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i) {
      const glm::ivec2 s = at(i, j);
      for (int c = 0; c < im.channels; ++c) out.at(i, j, c) = im.at(s.x, s.y, c);
    }
  return out;
}

// The quad of mip_quad.h (uv over [0, 4]², repeat) with these three textures.
Scene quad(Image base, Image mr, Image normal) {
  Scene s = textured_quad(1, [](int, int) { return kE; });
  s.images[0].pixels = std::move(base);
  s.images[1].pixels = std::move(mr);
  s.images[2].pixels = std::move(normal);
  return s;
}

void expect_no_warning(const Scene& s, const std::string& what) {
  Prepared p(s);
  EXPECT_NE(p.mips->find(0), nullptr) << what;
  EXPECT_TRUE(p.mips->warnings(TextureFilter::brdf).empty())
      << what << ": " << p.mips->warnings(TextureFilter::brdf).front();
}

// The two scenes render alike under `brdf` (and `param`), head-on (texels of level 2) and at 60°
// (anisotropic footprints), at the same seed. Bound: the two grids are equal texel for texel, so
// every lookup is; only a level-0 hit of a normal-mapped texel is shaded from the textures themselves,
// where one float rounding of a transformed uv at a texel edge could pick the neighbour, a pixel's
// share of which is far below the bound. The renders' noise (another seed) is above it by orders.
void expect_renders_alike(const Scene& a, const Scene& b, const std::string& what) {
  for (const TextureFilter f : {TextureFilter::brdf, TextureFilter::param})
    for (const glm::vec3& view : {glm::vec3(0, 0, 1), tilted(60, 30)}) {
      const Image x = render_quad(a, f, 4, view).radiance(), y = render_quad(b, f, 4, view).radiance();
      double worst = 0, scale = 0;
      for (std::size_t k = 0; k < x.pixels.size(); ++k) {
        worst = std::max(worst, double(std::abs(x.pixels[k] - y.pixels[k])));
        scale = std::max(scale, double(std::abs(y.pixels[k])));
      }
      EXPECT_LE(worst, 1e-6 * scale) << what << ", " << filter_name(f) << ", view z " << view.z;
      EXPECT_GT(scale, 0.0) << what;
    }
}

// A normal map tiled twice and shifted by KHR_texture_transform (scale 2, offset (¼, ½)) beside base
// colour and metallic-roughness maps with none: the grid follows the untransformed maps at twice their
// size (the normal map's texels across their unit), and equals the scene whose normal map is tiled and
// shifted by hand: grid texel (i, j) reads the normal map's texel (i + 16, j + 32) mod 64 (t = 2·uv +
// offset, 64 texels), the others' (i/2, j/2).
TEST(MipMappings, TransformedNormalMapJoinsTheGridAsIfTiledByHand) {
  const Image base = slot_image(64, 64, 1, Slot::base), mr = slot_image(64, 64, 2, Slot::mr),
              normal = slot_image(64, 64, 3, Slot::normal);
  Scene a = quad(base, mr, normal);
  a.materials[0].normal_texture.transform = TextureTransform::make({0.25f, 0.5f}, 0.0f, {2.0f, 2.0f});
  expect_no_warning(a, "normal map transformed");
  const auto half = [](int i, int j) { return glm::ivec2(i / 2, j / 2); };
  const Scene b =
      quad(rebaked(base, 128, 128, half), rebaked(mr, 128, 128, half),
           rebaked(normal, 128, 128, [](int i, int j) { return glm::ivec2((i + 16) % 64, (j + 32) % 64); }));
  {
    Prepared p(a);
    p.mips->prepare(TextureFilter::level0);
    EXPECT_EQ(p.mips->find(0)->texture().extent(), (Extent{128, 128}));
    EXPECT_TRUE(p.mips->find(0)->level0_exact());
  }
  expect_renders_alike(a, b, "normal map transformed");
}

// Sizes whose ratio is not whole (48×64 against 64×64): the grid takes the smallest common multiple
// across, 192 (4 texels of the 48, 3 of the 64), and equals the scene rebaked by hand at 192×64.
TEST(MipMappings, SizesThatDoNotDivideJoinAnExactGrid) {
  const Image base = slot_image(48, 64, 4, Slot::base), mr = slot_image(48, 64, 5, Slot::mr),
              normal = slot_image(64, 64, 6, Slot::normal);
  const Scene a = quad(base, mr, normal);
  expect_no_warning(a, "48 and 64 across");
  {
    Prepared p(a);
    p.mips->prepare(TextureFilter::level0);
    EXPECT_EQ(p.mips->find(0)->texture().extent(), (Extent{192, 64}));
  }
  const auto quarter = [](int i, int j) { return glm::ivec2(i / 4, j); };
  const Scene b = quad(rebaked(base, 192, 64, quarter), rebaked(mr, 192, 64, quarter),
                       rebaked(normal, 192, 64, [](int i, int j) { return glm::ivec2(i / 3, j); }));
  expect_renders_alike(a, b, "48 and 64 across");
}

// Wrap modes: a mirrored-repeat normal map tiled twice (scale 2) repeats with the others' grid where
// the quad's uv leave [0, 1] (mirrored repeat's period is 2), and equals the scene whose normal map is
// mirrored by hand: grid texel i reads texel i for i < 64, 127 − i after. Inside [0, 1] the wrap modes
// never act: a quad whose uv stay there takes a clamped normal map and a mirrored metallic-roughness
// map beside a repeating base colour as if all repeated.
TEST(MipMappings, WrapModesJoinTheGridWhereTheyAgreeOnTheSurface) {
  const Image base = slot_image(64, 64, 7, Slot::base), mr = slot_image(64, 64, 8, Slot::mr),
              normal = slot_image(64, 64, 9, Slot::normal);
  Scene a = quad(base, mr, normal);
  a.materials[0].normal_texture.transform = TextureTransform::make({0.0f, 0.0f}, 0.0f, {2.0f, 2.0f});
  a.textures[2].sampler.wrap_s = a.textures[2].sampler.wrap_t = WrapMode::mirrored_repeat;
  expect_no_warning(a, "mirrored normal map");
  const auto half = [](int i, int j) { return glm::ivec2(i / 2, j / 2); };
  const auto mirror = [](int i) { return i < 64 ? i : 127 - i; };
  const Scene b =
      quad(rebaked(base, 128, 128, half), rebaked(mr, 128, 128, half),
           rebaked(normal, 128, 128, [&](int i, int j) { return glm::ivec2(mirror(i), mirror(j)); }));
  expect_renders_alike(a, b, "mirrored normal map");

  Scene inside = quad(base, mr, normal);
  inside.meshes[0].primitives[0].texcoords[0] = {{0, 1}, {1, 1}, {1, 0}, {0, 0}};
  Scene repeating = inside;
  inside.textures[2].sampler.wrap_s = WrapMode::clamp_to_edge;
  inside.textures[1].sampler.wrap_t = WrapMode::mirrored_repeat;
  expect_no_warning(inside, "wrap modes inside [0, 1]");
  expect_renders_alike(inside, repeating, "wrap modes inside [0, 1]");
}

// An exact grid's level-0 texel at any uv the surface reaches is, for each texture, the texel the
// level0 lookup reads there (textures/sampler.h sample, nearest, with the texture's transform and
// wrap modes): base colour, roughness, metallic and the normal's z. Sizes, scales (one negative),
// offsets, turns and wrap modes differ between the three.
TEST(MipMappings, ExactGridHoldsEveryTexturesLevel0Lookup) {
  Scene s = quad(slot_image(32, 32, 10, Slot::base), slot_image(64, 32, 11, Slot::mr),
                 slot_image(32, 32, 12, Slot::normal));
  // Turned by a quarter: its s runs along the grid's t, 2 periods a grid period, its t along s, 3.
  s.materials[0].normal_texture.transform =
      TextureTransform::make({0.5f, 0.25f}, glm::radians(90.0f), {2.0f, 3.0f});
  // Mirrored by its transform along s: a grid texel's edges map to the opposite edges of its texels.
  s.materials[0].metallic_roughness_texture.transform =
      TextureTransform::make({0.0f, 0.5f}, 0.0f, {-1.0f, 1.0f});
  // Mirrored along s, where it moves 3 periods a grid period (odd): it does not repeat with the grid.
  s.textures[2].sampler.wrap_s = WrapMode::mirrored_repeat;
  {
    Prepared p(s);
    EXPECT_EQ(p.mips->find(0), nullptr);
  }
  // Mirrored along t, where it moves 2 (even): it does.
  s.textures[2].sampler.wrap_s = WrapMode::repeat;
  s.textures[2].sampler.wrap_t = WrapMode::mirrored_repeat;
  Prepared p(s);
  ASSERT_NE(p.mips->find(0), nullptr);
  p.mips->prepare(TextureFilter::level0);
  const MaterialMip& mip = *p.mips->find(0);
  EXPECT_TRUE(mip.level0_exact());
  const MaterialTexels texels = mip.texture().level0_texels();
  auto look = [&](int slot, glm::vec2 uv) {
    const TextureRef& r = slot == 0   ? s.materials[0].base_color_texture
                          : slot == 1 ? s.materials[0].metallic_roughness_texture
                                      : s.materials[0].normal_texture;
    Sampler nearest = s.textures[std::size_t(slot)].sampler;
    nearest.filter = FilterMode::nearest;
    return sample(s.images[std::size_t(slot)].pixels, nearest, r.transform.apply(uv));
  };
  Rng rng(13, 1);
  for (int n = 0; n < 400; ++n) {
    const glm::vec2 uv(4 * rng.next_float(), 4 * rng.next_float());
    const glm::ivec2 t = mip.texture().nearest_texel(mip.to_texture({uv, {0, 0}, {0, 0}}).uv);
    const std::size_t k = texels.index(t.x, t.y);
    EXPECT_FLOAT_EQ(texels.base_color[k].x, linear(glm::vec3(look(0, uv))).x) << uv.x << "," << uv.y;
    EXPECT_FLOAT_EQ(texels.roughness[k], look(1, uv).y) << uv.x << "," << uv.y;
    EXPECT_FLOAT_EQ(texels.metallic[k], look(1, uv).z) << uv.x << "," << uv.y;
    EXPECT_NEAR(texels.normal[k].z, glm::normalize(2.0f * glm::vec3(look(2, uv)) - 1.0f).z, 1e-6f)
        << uv.x << "," << uv.y;
  }
}

// Level 0 of an exact grid is each texture's level0 lookup: a quad without a normal map (so level-0
// hits are shaded from the grid's texel, not from the textures) whose metallic-roughness map is tiled
// twice and shifted by half and a quarter, its texels about 8 pixels wide, renders under level0 as
// with no MIP data at all, the lobe of the grid texel against the textures' own BSDF (float
// arithmetic apart: 1e-5 of the brightest pixel).
TEST(MipMappings, ExactGridRendersLevel0AsTheTexturesDo) {
  Scene s = quad(slot_image(16, 16, 20, Slot::base), slot_image(16, 16, 21, Slot::mr), Image(1, 1, 3));
  s.materials[0].normal_texture = TextureRef{};
  s.materials[0].metallic_roughness_texture.transform =
      TextureTransform::make({0.5f, 0.25f}, 0.0f, {2.0f, 2.0f});
  s.meshes[0].primitives[0].texcoords[0] = {{0, 1}, {1, 1}, {1, 0}, {0, 0}};
  {
    Prepared p(s);
    ASSERT_NE(p.mips->find(0), nullptr);
    EXPECT_TRUE(p.mips->find(0)->level0_exact());
  }
  const Image none = render_quad(s, TextureFilter::level0, 4, {0, 0, 1}, 1.0f, 0, false, false).radiance();
  const Image level0 = render_quad(s, TextureFilter::level0, 4).radiance();
  double worst = 0, scale = 0;
  for (std::size_t k = 0; k < none.pixels.size(); ++k) {
    worst = std::max(worst, double(std::abs(level0.pixels[k] - none.pixels[k])));
    scale = std::max(scale, double(none.pixels[k]));
  }
  EXPECT_LE(worst, 1e-5 * scale);
  EXPECT_GT(scale, 0.0);
}

// A metallic-roughness map offset by a fraction of a texel (3.2 and 6.4 texels): every texel still
// spans one grid texel, shifted off the grid's edges, so the grid is not exact at level 0 and a level-0
// hit is shaded from the textures: level0 renders as with no MIP data at all, and so does brdf at a
// footprint of (nearly) nothing.
TEST(MipMappings, DisplacedGridLeavesLevel0HitsToTheTextures) {
  Scene s = quad(slot_image(32, 32, 14, Slot::base), slot_image(32, 32, 15, Slot::mr), Image(1, 1, 3));
  s.materials[0].normal_texture = TextureRef{};
  s.materials[0].metallic_roughness_texture.transform =
      TextureTransform::make({0.1f, 0.2f}, 0.0f, {1.0f, 1.0f});
  s.meshes[0].primitives[0].texcoords[0] = {{0, 1}, {1, 1}, {1, 0}, {0, 0}};  // a texel ≈ 4 pixels
  {
    Prepared p(s);
    ASSERT_NE(p.mips->find(0), nullptr);
    EXPECT_TRUE(p.mips->warnings(TextureFilter::brdf).empty());
    EXPECT_FALSE(p.mips->find(0)->level0_exact());
    p.mips->prepare(TextureFilter::level0);
    EXPECT_EQ(p.mips->find(0)->texture().extent(), (Extent{32, 32}));
  }
  const Image none = render_quad(s, TextureFilter::level0, 4, {0, 0, 1}, 1.0f, 0, false, false).radiance();
  const Image level0 = render_quad(s, TextureFilter::level0, 4).radiance();
  const Image brdf = render_quad(s, TextureFilter::brdf, 4, {0, 0, 1}, 1e-4f).radiance();
  EXPECT_EQ(level0.pixels, none.pixels);
  EXPECT_EQ(brdf.pixels, none.pixels);
}

// The quad's square cut into n×n cells, TEXCOORD_0 over [0, 4]² as before and TEXCOORD_1 =
// uv1(TEXCOORD_0) at each vertex.
void tessellate(Scene& s, int n, const std::function<glm::vec2(glm::vec2)>& uv1) {
  MeshPrimitive& p = s.meshes[0].primitives[0];
  p.positions.clear(), p.texcoords[0].clear(), p.texcoords[1].clear(), p.indices.clear();
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      const float x = float(i) / float(n), y = float(j) / float(n);
      p.positions.push_back({-4 + 8 * x, 4 - 8 * y, 0});
      p.texcoords[0].push_back({4 * x, 4 * y});
      p.texcoords[1].push_back(uv1({4 * x, 4 * y}));
    }
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const std::uint32_t a = std::uint32_t(j * (n + 1) + i), b = a + 1, d = a + std::uint32_t(n) + 1,
                          c = d + 1;
      p.indices.insert(p.indices.end(), {d, c, b, d, b, a});  // counter-clockwise seen from +z
    }
  p.normals.assign(p.positions.size(), {0, 0, 1});
  p.tangents.assign(p.positions.size(), {1, 0, 0, 1});
}

// A texture on TEXCOORD_1 joins the grid when TEXCOORD_1 is an affine function of TEXCOORD_0 over the
// vertices (render/uv_relation.h), its KHR_texture_transform composed with the relation: the same
// as TEXCOORD_0 (A = I, b = 0); twice it plus (¼, 0), the normal map's transform (scale ½, offset
// (−⅛, 0)) bringing it back onto TEXCOORD_0; turned by a quarter, uv1 = (4 − v0, u0), the
// metallic-roughness map's transform (a quarter turn back, offset (0, 4)) doing the same. Each takes
// part with no warning and renders as the scene whose textures all read TEXCOORD_0 untransformed. The
// fit reads the vertices the triangles reference, not the others an accessor holds.
TEST(MipMappings, TexturesOnAnAffinelyRelatedUvSetJoinTheGrid) {
  const Image base = slot_image(64, 64, 30, Slot::base), mr = slot_image(64, 64, 31, Slot::mr),
              normal = slot_image(64, 64, 32, Slot::normal);
  Scene one_set = quad(base, mr, normal);
  tessellate(one_set, 6, [](glm::vec2 uv) { return uv; });
  one_set.meshes[0].primitives[0].texcoords[1].clear();

  Scene identical = quad(base, mr, normal);
  tessellate(identical, 6, [](glm::vec2 uv) { return uv; });
  identical.materials[0].normal_texture.tex_coord = 1;
  // A vertex that no triangle references is never on the surface, whatever its uv.
  MeshPrimitive& p = identical.meshes[0].primitives[0];
  p.positions.push_back({0, 0, 1}), p.normals.push_back({0, 0, 1}), p.tangents.push_back({1, 0, 0, 1});
  p.texcoords[0].push_back({1, 1}), p.texcoords[1].push_back({3, -7});
  expect_no_warning(identical, "identical sets");
  {
    Prepared p(identical);
    ASSERT_NE(p.mips->find(0), nullptr);
    EXPECT_TRUE(p.mips->find(0)->texture_map(identical.materials[0].normal_texture).identity());
  }
  expect_renders_alike(identical, one_set, "identical sets");

  Scene scaled = quad(base, mr, normal);
  tessellate(scaled, 6, [](glm::vec2 uv) { return 2.0f * uv + glm::vec2(0.25f, 0.0f); });
  scaled.materials[0].normal_texture.tex_coord = 1;
  scaled.materials[0].normal_texture.transform = TextureTransform::make({-0.125f, 0.0f}, 0.0f, {0.5f, 0.5f});
  expect_no_warning(scaled, "scaled and offset");
  expect_renders_alike(scaled, one_set, "scaled and offset");

  Scene turned = quad(base, mr, normal);
  tessellate(turned, 6, [](glm::vec2 uv) { return glm::vec2(4.0f - uv.y, uv.x); });
  turned.materials[0].metallic_roughness_texture.tex_coord = 1;
  turned.materials[0].metallic_roughness_texture.transform =
      TextureTransform::make({0.0f, 4.0f}, glm::radians(90.0f), {1.0f, 1.0f});
  expect_no_warning(turned, "turned by a quarter");
  expect_renders_alike(turned, one_set, "turned by a quarter");
}

// A TEXCOORD_1 that no affine map makes of TEXCOORD_0 keeps the material at level0, its warning naming
// the sets, their textures and the miss against the tolerance: a swirl (each point turned about the
// centre by half its distance in radians); and two primitives each with an affine TEXCOORD_1 but not
// the same one (the second's shifted by ½ along u), whose least-squares fit over both is A = I,
// b = (¼, 0), missing every vertex by ¼ along u: 16 texels of the 64² normal map.
TEST(MipMappings, UnrelatedUvSetsKeepTheMaterialAtLevel0) {
  const Image base = slot_image(64, 64, 33, Slot::base), mr = slot_image(64, 64, 34, Slot::mr),
              normal = slot_image(64, 64, 35, Slot::normal);
  auto warning = [](const Scene& s) {
    Prepared p(s);
    EXPECT_EQ(p.mips->find(0), nullptr);
    const std::vector<std::string> w = p.mips->warnings(TextureFilter::brdf);
    return w.size() == 1 ? w[0] : std::string("no single warning");
  };
  auto expect_in = [](const std::string& w, const std::string& needle) {
    EXPECT_NE(w.find(needle), std::string::npos) << "'" << needle << "' in: " << w;
  };
  Scene swirl = quad(base, mr, normal);
  tessellate(swirl, 8, [](glm::vec2 uv) {
    const glm::vec2 d = uv - glm::vec2(2.0f);
    const float a = 0.5f * glm::length(d), c = std::cos(a), s = std::sin(a);
    return glm::vec2(2.0f) + glm::vec2(c * d.x - s * d.y, s * d.x + c * d.y);
  });
  swirl.materials[0].normal_texture.tex_coord = 1;
  const std::string w = warning(swirl);
  expect_in(w, "materials[0]");
  // The base colour, which could be held apart, is; the rest are named.
  expect_in(w, "TEXCOORD_0: metallicRoughnessTexture; TEXCOORD_1: normalTexture");
  expect_in(w, "TEXCOORD_1 is no affine function of TEXCOORD_0");
  expect_in(w, "texels of normalTexture, where 0.00098 are allowed");

  Scene two = quad(base, mr, normal);
  tessellate(two, 2, [](glm::vec2 uv) { return uv; });
  MeshPrimitive second = two.meshes[0].primitives[0];
  for (glm::vec3& p : second.positions) p.x += 10;
  for (glm::vec2& uv : second.texcoords[1]) uv.x += 0.5f;
  second.where = "meshes[0].primitives[1]";
  two.meshes[0].primitives.push_back(second);
  two.materials[0].normal_texture.tex_coord = 1;
  expect_in(warning(two), "misses one of meshes[0].primitives[0] by 16 texels of normalTexture");
}

// The tolerance is 1/1020 of a texel of the textures a relation places on the grid
// (render/uv_relation.h), in their own texels. TEXCOORD_1 is TEXCOORD_0 plus a checkerboard of ±δ along
// u on a 4×4 grid of vertices: a pattern that sums to nothing against 1, u and v, so the fit either
// way is the identity and misses every vertex by δ. With the metallic-roughness map on TEXCOORD_0 and
// the normal map on TEXCOORD_1 (no base colour texture, which could be held apart), δ of half the
// tolerance in texels of a 64² map joins and twice it does not; the same δ is refused when both maps
// are 256² or tiled 4 times by their transforms (four times the texels), and joins when only one is:
// the grid follows the fine one and places the coarse one.
TEST(MipMappings, UvRelationToleranceIsAFractionOfATexel) {
  auto scene = [](int mr_size, int normal_size, double texels_of_64, float tiles = 1.0f) {
    Scene s = quad(Image(1, 1, 3), slot_image(mr_size, mr_size, 36, Slot::mr),
                   slot_image(normal_size, normal_size, 37, Slot::normal));
    s.materials[0].base_color_texture = TextureRef{};
    for (TextureRef* r : {&s.materials[0].metallic_roughness_texture, &s.materials[0].normal_texture})
      r->transform = TextureTransform::make({0.0f, 0.0f}, 0.0f, {tiles, tiles});
    const float delta = float(texels_of_64 * kUvRelationTolerance / 64);
    tessellate(s, 3, [&](glm::vec2 uv) {
      const int parity = int(std::lround(uv.x * 3 / 4 + uv.y * 3 / 4)) % 2;
      return uv + glm::vec2(parity ? delta : -delta, 0.0f);
    });
    s.materials[0].normal_texture.tex_coord = 1;
    return s;
  };
  auto joins = [](const Scene& s) { return Prepared(s).mips->find(0) != nullptr; };
  EXPECT_TRUE(joins(scene(64, 64, 0.5)));
  EXPECT_FALSE(joins(scene(64, 64, 2.0)));
  EXPECT_FALSE(joins(scene(256, 256, 0.5)));
  EXPECT_FALSE(joins(scene(64, 64, 0.5, 4.0f)));
  EXPECT_TRUE(joins(scene(256, 64, 0.5)));
  EXPECT_TRUE(joins(scene(64, 256, 0.5)));
  // The accepted relation is the identity: the checkerboard is orthogonal to every affine map.
  const Scene s = scene(64, 64, 0.5);
  const Prepared p(s);
  ASSERT_NE(p.mips->find(0), nullptr);
  EXPECT_TRUE(p.mips->find(0)->texture_map(s.materials[0].normal_texture).identity());
}

// The mappings no grid serves leave the material to level0 with one warning naming the material and
// the textures, and what they lack.
TEST(MipMappings, MappingsNoGridServesAreNamed) {
  auto warned = [](Scene s, std::initializer_list<const char*> needles) {
    Prepared p(std::move(s));
    EXPECT_EQ(p.mips->find(0), nullptr);
    const std::vector<std::string> w = p.mips->warnings(TextureFilter::brdf);
    ASSERT_EQ(w.size(), 1u);
    for (const char* n : needles) EXPECT_NE(w[0].find(n), std::string::npos) << "'" << n << "' in: " << w[0];
    EXPECT_NE(w[0].find("materials[0]"), std::string::npos) << w[0];
  };
  const Image base = slot_image(16, 16, 16, Slot::base), mr = slot_image(16, 16, 17, Slot::mr),
              normal = slot_image(16, 16, 18, Slot::normal);
  {
    // Another uv set that no affine map relates to the grid's: two corners swapped, a bow tie.
    Scene s = quad(base, mr, normal);
    s.materials[0].metallic_roughness_texture.tex_coord = 1;
    s.meshes[0].primitives[0].texcoords[1] = {{0, 4}, {4, 4}, {0, 0}, {4, 0}};
    warned(std::move(s), {"TEXCOORD_0: normalTexture; TEXCOORD_1: metallicRoughnessTexture",
                          "no affine function", "only a baseColorTexture is held apart"});
  }
  {
    // A clamped normal map where the quad's uv reach [0, 4].
    Scene s = quad(base, mr, normal);
    s.textures[2].sampler.wrap_s = WrapMode::clamp_to_edge;
    warned(std::move(s), {"normalTexture", "clamp-to-edge", "[0, 4]"});
  }
  {
    // A scale of 1.5: no grid period is a whole number of the map's.
    Scene s = quad(base, mr, normal);
    s.materials[0].normal_texture.transform = TextureTransform::make({0, 0}, 0.0f, {1.5f, 1.0f});
    warned(std::move(s), {"normalTexture", "metallicRoughnessTexture", "1.5", "not a whole number"});
  }
  {
    // Sizes 25 and 32: a texel of 1.28 grid texels, whole at no multiple up to 4.
    Scene s = quad(slot_image(32, 32, 16, Slot::base), slot_image(25, 25, 19, Slot::mr),
                   slot_image(32, 32, 18, Slot::normal));
    warned(std::move(s), {"metallicRoughnessTexture's texels span 1.28 grid texels", "unevenly"});
  }
  {
    // Sizes 16 and 20: whole on a grid of 80² texels, more than four times 20².
    Scene s = quad(base, slot_image(20, 20, 19, Slot::mr), normal);
    warned(std::move(s), {"lie whole only on a grid of 80x80 texels", "more than four times"});
  }
  {
    // Turned by 30° on a quad whose uv stay in [0, 1] (so the wrap modes ask nothing).
    Scene s = quad(base, mr, normal);
    s.materials[0].normal_texture.transform =
        TextureTransform::make({0, 0}, glm::radians(30.0f), {1.0f, 1.0f});
    s.meshes[0].primitives[0].texcoords[0] = {{0, 1}, {1, 1}, {1, 0}, {0, 0}};
    warned(std::move(s), {"normalTexture", "turned by its KHR_texture_transform", "unevenly"});
  }
  {
    // Tiled 8 times over the others: a grid of 64 times their texels.
    Scene s = quad(base, mr, normal);
    s.materials[0].normal_texture.transform = TextureTransform::make({0, 0}, 0.0f, {8.0f, 8.0f});
    warned(std::move(s), {"normalTexture", "128x128", "more than four times"});
  }
}

}  // namespace
}  // namespace svbrdf
