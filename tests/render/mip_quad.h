#pragma once
// The textured quad of the MIP filter tests (mip_filter_test.cpp, mip_tint_test.cpp): texels that
// differ in every parameter, the quad that holds them in three glTF textures, its render under a
// directional light, and f_eff of brdf-mip.md computed from the texel values with gltf_eval, never
// from the renderer or the mip module.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <memory>
#include <span>
#include <string>

#include "appearance/frame.h"
#include "appearance/gltf.h"
#include "render/material_mips.h"
#include "render/renderer.h"
#include "render_test_scenes.h"
#include "textures/color.h"

namespace svbrdf::mip_quad {

using test::ortho_camera;

// One texel as stored in the three glTF textures.
struct TexelSpec {
  glm::vec3 srgb;  // base color, sRGB-encoded as glTF stores it
  float metallic;
  float roughness;
  glm::vec3 normal;  // unit, tangent space
};

inline glm::vec3 tilted(float deg, float azimuth_deg) {
  const float t = glm::radians(deg), p = glm::radians(azimuth_deg);
  return {std::sin(t) * std::cos(p), std::sin(t) * std::sin(p), std::cos(t)};
}

// Four texels that differ in every parameter, normals 20° apart around the geometric normal.
const TexelSpec kA{{0.8f, 0.25f, 0.1f}, 0.0f, 0.6f, tilted(20, 0)};
const TexelSpec kB{{0.9f, 0.75f, 0.35f}, 1.0f, 0.35f, tilted(20, 180)};
const TexelSpec kC{{0.15f, 0.4f, 0.85f}, 0.0f, 0.45f, tilted(20, 90)};
const TexelSpec kD{{0.95f, 0.95f, 0.95f}, 1.0f, 0.25f, tilted(20, 270)};
// The specular layer of A B C D for the specular tests: specularTexture.a and specularColorTexture
// (sRGB-encoded).
constexpr float kSpecularWeight[4] = {1.0f, 0.05f, 0.2f, 0.8f};
const glm::vec3 kSpecularSrgb[4] = {{1.0f, 1.0f, 1.0f}, {0.9f, 0.5f, 0.2f}, {0.3f, 0.8f, 0.9f}, {0.7f, 0.7f, 0.7f}};
// A plain texel for the other squares of the checkerboard.
const TexelSpec kE{{0.5f, 0.6f, 0.4f}, 0.0f, 0.7f, {0, 0, 1}};

inline Rgb linear(const glm::vec3& srgb) {
  const ColorConfig& c = ColorConfig::builtin();
  return {c.srgb_texture_to_linear(srgb.x), c.srgb_texture_to_linear(srgb.y), c.srgb_texture_to_linear(srgb.z)};
}

// The normal as the renderer reads it back from the map (rgb = n/2 + 1/2, spec: n = normalize(2·rgb − 1)).
inline glm::vec3 stored_normal(const glm::vec3& n) { return glm::normalize(2.0f * (0.5f * n + 0.5f) - 1.0f); }

// f_eff of brdf-mip.md in double-checked float: the glTF BRDF about n, times max(0, n·wi)/wi.z.
inline glm::dvec3 f_eff(const Rgb& base, float metallic, float roughness, const glm::vec3& n, const glm::vec3& wi,
                 const glm::vec3& wo) {
  if (wi.z <= 0 || wo.z <= 0 || glm::dot(n, wi) <= 0 || glm::dot(n, wo) <= 0) return glm::dvec3(0);
  const Frame f = Frame::from_normal(n);
  return glm::dvec3(gltf_eval({base, metallic, roughness}, f.to_local(wi), f.to_local(wo))) *
         double(glm::dot(n, wi)) / double(wi.z);
}
inline glm::dvec3 f_eff(const TexelSpec& t, const glm::vec3& wi, const glm::vec3& wo) {
  return f_eff(linear(t.srgb), t.metallic, t.roughness, stored_normal(t.normal), wi, wo);
}

// The mean f_eff of a set of texels (a coarse texel's exact BRDF).
inline glm::dvec3 mean_f_eff(std::initializer_list<TexelSpec> texels, const glm::vec3& wi, const glm::vec3& wo) {
  glm::dvec3 s(0);
  for (const TexelSpec& t : texels) s += f_eff(t, wi, wo);
  return s / double(texels.size());
}

// f_eff of one texel with the texels' mean parameters (brdf-mip.md, `param`).
inline glm::dvec3 param_f_eff(std::initializer_list<TexelSpec> texels, const glm::vec3& wi, const glm::vec3& wo) {
  Rgb c(0);
  float m = 0, r = 0;
  glm::vec3 n(0);
  for (const TexelSpec& t : texels) c += linear(t.srgb), m += t.metallic, r += t.roughness, n += stored_normal(t.normal);
  const float k = float(texels.size());
  return f_eff(c / k, m / k, r / k, glm::normalize(n), wi, wo);
}

// A material of three float textures (base color, metallic-roughness, normal) of size×size texels,
// texel (i, j) given by `at`, on a square of side 8 in z = 0 (front +z, tangent +x, bitangent +y)
// whose uv runs over [0, 4]² (repeat), uv (0, 0) at the top-left corner (−4, +4).
template <class At>
Scene textured_quad(int size, At at) {
  Scene s;
  Image base(size, size, 3), mr(size, size, 3), normal(size, size, 3);
  for (int j = 0; j < size; ++j)
    for (int i = 0; i < size; ++i) {
      const TexelSpec t = at(i, j);
      const glm::vec3 enc = 0.5f * t.normal + 0.5f;
      for (int c = 0; c < 3; ++c) base.at(i, j, c) = t.srgb[c], normal.at(i, j, c) = enc[c];
      mr.at(i, j, 0) = 1.0f, mr.at(i, j, 1) = t.roughness, mr.at(i, j, 2) = t.metallic;
    }
  for (Image* im : {&base, &mr, &normal}) test::add_image_texture(s, std::move(*im));
  MaterialDesc m;
  m.where = "materials[0]";
  m.base_color_texture.texture = 0;
  m.metallic_roughness_texture.texture = 1;
  m.normal_texture.texture = 2;
  s.materials.push_back(m);
  MeshPrimitive p;
  p.positions = {{-4, -4, 0}, {4, -4, 0}, {4, 4, 0}, {-4, 4, 0}};
  p.normals.assign(4, {0, 0, 1});
  p.texcoords[0] = {{0, 4}, {4, 4}, {4, 0}, {0, 0}};
  p.tangents.assign(4, {1, 0, 0, 1});
  p.indices = {0, 1, 2, 0, 2, 3};
  p.material = 0;
  p.where = "meshes[0].primitives[0]";
  Mesh mesh;
  mesh.primitives.push_back(std::move(p));
  s.meshes.push_back(std::move(mesh));
  s.instances.push_back({0, 0, glm::dmat4(1.0)});
  return s;
}

// Texel (i, j) of the 2×2 pattern A B / C D.
inline const TexelSpec& pattern_texel(int i, int j) { return j % 2 ? (i % 2 ? kD : kC) : (i % 2 ? kB : kA); }

// The 2×2 pattern A B / C D everywhere: every texel of level ≥ 1 covers the same texels.
inline Scene periodic_quad(int size = 256) { return textured_quad(size, pattern_texel); }

// The mean of f(i, j) over the 8 × 8 texels of a level-3 texel of a quad whose texture repeats every 8
// texels (every coarse texel then covers the same ones).
template <class F>
glm::dvec3 block_mean(const F& f) {
  glm::dvec3 mean(0);
  for (int j = 0; j < 8; ++j)
    for (int i = 0; i < 8; ++i) mean += f(i, j) / 64.0;
  return mean;
}

// Blocks of 8×8 texels (the texels of level 3) in a checkerboard: the pattern A B / C D on even
// blocks (P), plain E on odd ones (Q).
inline Scene checker_quad(int size = 256) {
  return textured_quad(size, [](int i, int j) {
    if ((i / 8 + j / 8) % 2) return kE;
    return pattern_texel(i, j);
  });
}

const glm::vec3 kWi = tilted(35, 20);  // toward the light
constexpr float kE0 = 2.0f;            // its irradiance

// A sun of irradiance kE0 toward `wi` (from the quad).
inline LightDesc sun(const glm::vec3& wi) {
  LightDesc l;
  l.type = LightDesc::Type::directional;
  l.intensity = kE0;
  l.direction = -wi;
  return l;
}

// The quad under the sun from kWi (a scene with lights of its own: under those instead), seen by an orthographic camera from `view` (a unit direction
// toward the camera) with half height 1 at 32×32 pixels: head-on, a pixel spans 1/16 of the square,
// 256·4/8/16 = 8 texels of a 256² texture: level 3. `with_mips` false renders it with no MIP data.
inline Film render_quad(Scene s, TextureFilter filter, int spp, const glm::vec3& view = {0, 0, 1}, float footprint_scale = 1.0f,
                 int threads = 0, bool aovs = false, bool with_mips = true) {
  if (s.lights.empty()) s.lights.push_back(sun(kWi));
  s.cameras.push_back(ortho_camera(5.0f * view, {0, 0, 0}, 1.0f, std::abs(view.y) > 0.9f ? glm::vec3(0, 0, -1) : glm::vec3(0, 1, 0)));
  SceneSetup setup;
  setup.width = setup.height = 32;
  setup.env = "0,0,0";
  const PreparedScene prepared(std::move(s), setup);
  RenderOptions o;
  o.spp = spp;
  o.threads = threads;
  o.seed = 3;
  o.aovs = aovs;
  o.integrator.filter = filter;
  o.integrator.max_depth = 1;  // light reflected once; what leaves the plane meets the black sky
  o.integrator.footprint_scale = footprint_scale;
  o.integrator.footprints = aovs;
  // Without MIP data every material is shaded as one the MIP maps leave out (level0 lookups).
  RenderWorld world = prepared.world();
  if (!with_mips) world.mips = nullptr;
  return render(world, o);
}

inline glm::dvec3 pixel(const Image& im, int x, int y) {
  const float* p = &im.pixels[(std::size_t(y) * im.width + x) * im.channels];
  return {p[0], p[1], p[2]};
}

inline glm::dvec3 image_mean(const Image& im) {
  glm::dvec3 s(0);
  for (int y = 0; y < im.height; ++y)
    for (int x = 0; x < im.width; ++x) s += pixel(im, x, y);
  return s / double(im.width * im.height);
}

// The standard error of an image's mean: where every pixel covers the same blocks of the periodic quad
// (head-on, one 8 × 8 block; from 65° a stretch of them), the pixels are independent estimates of one
// value, and their spread says how far their mean may lie from it.
inline glm::dvec3 standard_error(const Image& im) {
  const glm::dvec3 mean = image_mean(im);
  glm::dvec3 ss(0);
  for (int y = 0; y < im.height; ++y)
    for (int x = 0; x < im.width; ++x) ss += (pixel(im, x, y) - mean) * (pixel(im, x, y) - mean);
  const double n = double(im.width) * im.height;
  return glm::sqrt(ss / (n - 1) / n);
}

inline void expect_within(const glm::dvec3& got, const glm::dvec3& want, const glm::dvec3& se, const std::string& what) {
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(got[c], want[c], 4 * se[c]) << what << " channel " << c;
}

inline void expect_rgb_near(const glm::dvec3& got, const glm::dvec3& want, double rel, const std::string& what) {
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(got[c], want[c], rel * std::max(want[c], 1e-3)) << what << " channel " << c;
}

struct Prepared {
  Scene scene;
  std::unique_ptr<TextureSet> textures;
  std::unique_ptr<SceneMips> mips;
  explicit Prepared(Scene s) : scene(std::move(s)) {
    textures = std::make_unique<TextureSet>(scene);
    mips = std::make_unique<SceneMips>(scene, *textures);
  }
};

inline bool same_lobes(std::span<const Lobe> a, std::span<const Lobe> b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(Lobe)) == 0;
}

}  // namespace svbrdf::mip_quad
