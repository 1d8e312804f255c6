// The glTF extension layers through the whole renderer (loader's MaterialDesc → shading_params →
// SurfaceBsdf → integrator), against closed forms of the extensions' texts.
#include <gtest/gtest.h>

#include <cmath>

#include "gltf/scene_reader.h"
#include "gltf_test_files.h"
#include "render_test_scenes.h"
#include "textures/image.h"

namespace svbrdf {
namespace {

using namespace test;

glm::vec3 pixel(const Image& im, int x, int y) {
  const float* p = &im.pixels[(std::size_t(y) * im.width + x) * im.channels];
  return {p[0], p[1], p[2]};
}

double mean_luma(const Image& im) {
  double s = 0;
  for (int y = 0; y < im.height; ++y)
    for (int x = 0; x < im.width; ++x) s += pixel(im, x, y).y;
  return s / (im.width * im.height);
}

// A coat over black in a uniform environment of radiance L, seen head-on: every pixel reflects
// L·0.04, the coat's Fresnel at normal incidence (KHR_materials_clearcoat: ior 1.5), when smooth.
TEST(LayeredRender, SmoothCoatOverBlackReflectsItsF0) {
  Scene s;
  MaterialDesc m = lambertian(Rgb(0.0f));
  m.clearcoat = 1.0f;
  m.clearcoat_roughness = 0.0f;
  s.materials.push_back(m);
  add_quad(s, 0, glm::dmat4(1.0), 8.0f);
  s.cameras.push_back(ortho_camera({0, 0, 5}, {0, 0, 0}, 1.0f));
  SceneSetup setup;
  setup.width = setup.height = 8;
  setup.env = "2,2,2";
  const Image im = render_scene(std::move(s), setup, 16).radiance();
  EXPECT_NEAR(mean_luma(im), 2.0 * 0.04, 2.0 * 0.04 * 0.01);
}

// The coat darkens the emission beneath it by 1 − clearcoat·Fc(view) (the extension's "Emission"):
// an emissive quad under a full coat, black environment, seen head-on and from 60°.
TEST(LayeredRender, CoatDarkensEmission) {
  for (const float view_deg : {0.0f, 60.0f}) {
    Scene s;
    MaterialDesc m = lambertian(Rgb(0.0f));
    m.emissive = Rgb(1.0f, 0.5f, 0.25f);
    m.clearcoat = 1.0f;
    s.materials.push_back(m);
    add_quad(s, 0, glm::dmat4(1.0), 20.0f);
    const float a = glm::radians(view_deg);
    s.cameras.push_back(ortho_camera({5 * std::sin(a), 0, 5 * std::cos(a)}, {0, 0, 0}, 1.0f));
    SceneSetup setup;
    setup.width = setup.height = 4;
    setup.env = "0,0,0";
    const Image im = render_scene(std::move(s), setup, 1).radiance();
    const double fc = 0.04 + 0.96 * std::pow(1.0 - std::cos(double(a)), 5.0);
    for (int y = 0; y < 4; ++y)
      for (int x = 0; x < 4; ++x)
        EXPECT_NEAR(pixel(im, x, y).x, 1.0 - fc, 1e-5) << "view " << view_deg << "°";
  }
}

// KHR_materials_anisotropy's direction follows the primitive's tangent (x here) turned
// counter-clockwise toward the bitangent (y) by anisotropyRotation. A white metal (Fresnel 1) under
// a directional light from +x, seen from a direction off the plane of incidence: each rotation's
// pixel is the extension's anisotropic D·V at that geometry times E·cosθi, and rotations of
// opposite sign differ.
TEST(LayeredRender, AnisotropyDirectionFollowsTheTangentAndRotation) {
  const double theta = glm::radians(40.0), view = glm::radians(50.0), azimuth = glm::radians(200.0);
  const glm::dvec3 wi(std::sin(theta), 0, std::cos(theta));
  const glm::dvec3 wo(std::sin(view) * std::cos(azimuth), std::sin(view) * std::sin(azimuth), std::cos(view));
  auto render_with = [&](float rotation) {
    Scene s;
    MaterialDesc m;
    m.base_color = Rgb(1.0f);
    m.metallic = 1.0f;
    m.roughness = 0.3f;
    m.anisotropy_strength = 1.0f;
    m.anisotropy_rotation = rotation;
    s.materials.push_back(m);
    add_quad(s, 0, glm::dmat4(1.0), 20.0f);
    LightDesc sun;
    sun.type = LightDesc::Type::directional;
    sun.intensity = 1.0f;
    sun.direction = -glm::vec3(wi);
    s.lights.push_back(sun);
    s.cameras.push_back(ortho_camera(glm::vec3(5.0 * wo), {0, 0, 0}, 1.0f));
    SceneSetup setup;
    setup.width = setup.height = 4;
    setup.env = "0,0,0";
    return pixel(render_scene(std::move(s), setup, 1).radiance(), 1, 1).x;
  };
  // f·E·cosθi with f = D·V of the extension's anisotropic GGX: αt = mix(α, 1, 1²) = 1 along the
  // direction t, αb = α = 0.3² across it.
  const double alpha = 0.09, at = 1.0;
  auto expected = [&](double rotation) {
    const glm::dvec3 t(std::cos(rotation), std::sin(rotation), 0), n(0, 0, 1), b = glm::cross(n, t);
    const glm::dvec3 h = glm::normalize(wi + wo);
    const double a2 = at * alpha;
    const glm::dvec3 f(alpha * glm::dot(t, h), at * glm::dot(b, h), a2 * glm::dot(n, h));
    const double w2 = a2 / glm::dot(f, f), d = a2 * w2 * w2 / 3.14159265358979;
    const double gv = wi.z * glm::length(glm::dvec3(at * glm::dot(t, wo), alpha * glm::dot(b, wo), wo.z));
    const double gl = wo.z * glm::length(glm::dvec3(at * glm::dot(t, wi), alpha * glm::dot(b, wi), wi.z));
    return d * 0.5 / (gv + gl) * wi.z;
  };
  ASSERT_GT(std::abs(expected(0.5) - expected(-0.5)), 0.2 * expected(-0.5));  // the geometry tells them apart
  for (const double r : {0.0, 0.5, -0.5, 1.5707963}) {
    const double want = expected(r);
    EXPECT_NEAR(render_with(float(r)), want, 1e-4 * want) << "rotation " << r;
  }
}

// KHR_materials_diffuse_transmission through the renderer: a thin quad (the specular layer off, so
// its base is Lambertian) that transmits a share dt of what it scatters, lit by a directional light
// of E at 60°, seen head-on from the front: lit from the front it reflects (1 − dt)·ρ/π·E·cos60°,
// lit from behind it transmits dt·c/π·E·cos60°.
TEST(LayeredRender, DiffuseTransmissionLightsTheFrontFromBehind) {
  const Rgb rho(0.2f, 0.5f, 0.8f), color(0.9f, 0.6f, 0.3f);
  const float dt = 0.4f, E = 2.0f, theta = glm::radians(60.0f);
  for (const float side : {1.0f, -1.0f}) {
    Scene s;
    MaterialDesc m = lambertian(rho);
    m.diffuse_transmission = dt;
    m.diffuse_transmission_color = color;
    m.double_sided = true;
    s.materials.push_back(m);
    add_quad(s, 0, glm::dmat4(1.0), 8.0f);
    LightDesc sun;
    sun.type = LightDesc::Type::directional;
    sun.intensity = E;
    sun.direction = -glm::vec3(std::sin(theta), 0.0f, side * std::cos(theta));
    s.lights.push_back(sun);
    s.cameras.push_back(ortho_camera({0, 0, 5}, {0, 0, 0}, 1.0f));
    SceneSetup setup;
    setup.width = setup.height = 4;
    setup.env = "0,0,0";
    const Image im = render_scene(std::move(s), setup, 1).radiance();
    const Rgb want = (side > 0 ? (1.0f - dt) * rho : dt * color) / 3.14159265f * E * std::cos(theta);
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(pixel(im, 1, 1)[c], want[c], 1e-5f * want[c] + 1e-7f) << (side > 0 ? "front" : "behind");
  }
}

// A file that uses every material extension the renderer reads (and texture transforms, variants
// and punctual lights) on one quad loads without a single warning, and each variant renders a finite,
// lit image. (Compressed geometry has its own tests: compressed_mesh_test.cpp.)
TEST(LayeredRender, EveryExtensionLoadsWithoutAWarningAndRenders) {
  test::TempDir dir;
  test::GltfQuad q;
  q.texcoords = {0, 0, 1, 0, 1, 1, 0, 1};
  Image px(2, 2, 4);
  for (float& v : px.pixels) v = 0.75f;
  write_image(dir.path() / "px.png", px, PixelFormat::uint8);
  const std::string tex = R"({"index": 0, "extensions": {"KHR_texture_transform": {"scale": [2, 2], "rotation": 0.3}}})";
  q.materials = R"([{"name": "Everything", "pbrMetallicRoughness": {"baseColorTexture": )" + tex + R"(},
       "extensions": {
         "KHR_materials_emissive_strength": {"emissiveStrength": 2},
         "KHR_materials_ior": {"ior": 1.45},
         "KHR_materials_specular": {"specularFactor": 0.8, "specularColorFactor": [1, 0.9, 0.8]},
         "KHR_materials_transmission": {"transmissionFactor": 0.3},
         "KHR_materials_volume": {"thicknessFactor": 0.1, "attenuationDistance": 2, "attenuationColor": [0.9, 0.8, 0.7]},
         "KHR_materials_dispersion": {"dispersion": 0.5},
         "KHR_materials_diffuse_transmission": {"diffuseTransmissionFactor": 0.2},
         "KHR_materials_diffuse_roughness": {"diffuseRoughnessFactor": 0.4},
         "KHR_materials_clearcoat": {"clearcoatFactor": 0.5, "clearcoatNormalTexture": )" + tex + R"(},
         "KHR_materials_anisotropy": {"anisotropyStrength": 0.5, "anisotropyTexture": )" + tex + R"(},
         "KHR_materials_sheen": {"sheenColorFactor": [0.3, 0.2, 0.1], "sheenRoughnessFactor": 0.5},
         "KHR_materials_iridescence": {"iridescenceFactor": 0.5, "iridescenceThicknessTexture": )" + tex + R"(}}},
     {"name": "Unlit", "extensions": {"KHR_materials_unlit": {}}}])";
  q.primitive_extra = R"(, "material": 0, "extensions": {"KHR_materials_variants": {"mappings": [
       {"material": 1, "variants": [1]}]}})";
  q.nodes = R"([{"mesh": 0}, {"translation": [0, 0, 3], "extensions": {"KHR_lights_punctual": {"light": 0}}}])";
  q.scene_nodes = "[0, 1]";
  q.top_extra = R"(, "textures": [{"source": 0}], "images": [{"uri": "px.png"}],
      "extensions": {"KHR_lights_punctual": {"lights": [{"type": "point", "intensity": 2000}]},
                     "KHR_materials_variants": {"variants": [{"name": "Layered"}, {"name": "Flat"}]}},
      "extensionsUsed": ["KHR_texture_transform", "KHR_materials_emissive_strength", "KHR_materials_ior",
        "KHR_materials_specular", "KHR_materials_transmission", "KHR_materials_volume", "KHR_materials_dispersion",
        "KHR_materials_diffuse_transmission", "KHR_materials_diffuse_roughness", "KHR_materials_clearcoat",
        "KHR_materials_anisotropy", "KHR_materials_sheen", "KHR_materials_iridescence", "KHR_materials_unlit",
        "KHR_materials_variants", "KHR_lights_punctual"])";
  const auto file = dir.write("every.gltf", q.json());
  for (const std::string variant : {"Layered", "Flat"}) {
    LoadOptions o;
    o.variant = variant;
    Scene s = load_gltf(file, o);
    for (const std::string& w : s.warnings) ADD_FAILURE() << variant << ": " << w;
    s.cameras.push_back(ortho_camera({0.5f, 0.5f, 4.0f}, {0.5f, 0.5f, 0.0f}, 0.4f));
    SceneSetup setup;
    setup.width = setup.height = 8;
    setup.env = "0.2,0.2,0.2";
    const Image im = render_scene(std::move(s), setup, 4).radiance();
    for (const float v : im.pixels) ASSERT_TRUE(std::isfinite(v)) << variant;
    EXPECT_GT(mean_luma(im), 0.01) << variant;
  }
}

// A closed box with flat, outward faces: the boundary of a volume.
void add_box(Scene& s, int material, const glm::vec3& half) {
  MeshPrimitive p;
  for (int axis = 0; axis < 3; ++axis)
    for (const float sign : {1.0f, -1.0f}) {
      glm::vec3 n(0.0f), u(0.0f);
      n[axis] = sign;
      u[(axis + 1) % 3] = 1.0f;
      const glm::vec3 v = glm::cross(n, u);  // u × v = n: counter-clockwise seen from outside
      const glm::vec3 c = n * half[axis];
      const float hu = half[(axis + 1) % 3], hv = glm::dot(glm::abs(v), half);
      const auto base = std::uint32_t(p.positions.size());
      for (const glm::vec2 k : {glm::vec2(-1, -1), glm::vec2(1, -1), glm::vec2(1, 1), glm::vec2(-1, 1)}) {
        p.positions.push_back(c + k.x * hu * u + k.y * hv * v);
        p.normals.push_back(n);
      }
      for (const std::uint32_t i : {0u, 1u, 2u, 0u, 2u, 3u}) p.indices.push_back(base + i);
    }
  p.material = material;
  p.where = "test box";
  Mesh m;
  m.primitives.push_back(std::move(p));
  s.meshes.push_back(std::move(m));
  s.instances.push_back({int(s.meshes.size()) - 1, int(s.instances.size()), glm::dmat4(1.0)});
}

// KHR_materials_volume: a smooth glass slab (ior 1.5, transmission 1) of thickness t between the
// camera and an emitter of radiance Le, seen head-on, black elsewhere. With attenuationColor c at
// attenuationDistance d the inside keeps e^(−τ), τ = −ln(c)·t/d, and the slab lets through
//   Le·(1 − F)²·e^(−τ) / (1 − F²·e^(−2τ)),  F = ((1.5 − 1)/(1.5 + 1))² = 0.04,
// the inter-reflections summed in closed form (the light reflected toward the camera's side meets
// the black sky).
constexpr float kSlabThickness = 0.5f, kSlabAttenuationDistance = 0.5f;

// The slab's head-on 8×8 image: a smooth glass box (ior 1.5, transmission 1) of thickness
// kSlabThickness with attenuationColor c and the given dispersion, before an emitter of radiance
// `emitted`, black elsewhere.
Image glass_slab_image(float c, float dispersion, const Rgb& emitted, int spp) {
  Scene s;
  MaterialDesc glass;
  glass.base_color = Rgb(1.0f);
  glass.metallic = 0.0f;
  glass.roughness = 0.0f;
  glass.transmission = 1.0f;
  glass.thickness = kSlabThickness;
  glass.attenuation_distance = kSlabAttenuationDistance;
  glass.attenuation_color = Rgb(c);
  glass.dispersion = dispersion;
  s.materials.push_back(glass);
  MaterialDesc light = lambertian(Rgb(0.0f));
  light.emissive = emitted;
  s.materials.push_back(light);
  add_box(s, 0, {4.0f, 4.0f, 0.5f * kSlabThickness});
  add_quad(s, 1, glm::translate(glm::dmat4(1.0), glm::dvec3(0, 0, -2)), 20.0f);
  s.cameras.push_back(ortho_camera({0, 0, 5}, {0, 0, 0}, 1.0f));
  SceneSetup setup;
  setup.width = setup.height = 8;
  setup.env = "0,0,0";
  return render_scene(std::move(s), setup, spp).radiance();
}

// What the slab lets through head-on: (1 − F)²·e^(−τ) / (1 − F²·e^(−2τ)), F = 0.04,
// τ = −ln(c)·t/d.
double slab_transmittance(float c) {
  const double f = 0.04, tau = -std::log(double(c)) * kSlabThickness / kSlabAttenuationDistance;
  return (1 - f) * (1 - f) * std::exp(-tau) / (1 - f * f * std::exp(-2 * tau));
}

TEST(LayeredRender, GlassSlabTransmitsBeerLambertAndFresnel) {
  for (const float c : {1.0f, 0.5f}) {
    const double want = slab_transmittance(c);
    EXPECT_NEAR(mean_luma(glass_slab_image(c, 0.0f, Rgb(1.0f), 256)), want, 0.01 * want) << "attenuationColor " << c;
  }
}

// KHR_materials_dispersion: a path that refracts through a dispersive volume follows one channel,
// drawn with probability 1/3 and weighted 3×. Head-on every channel refracts straight through, so
// a dispersive slab must transmit what the same slab without dispersion does, channel by channel
// (the closed form of GlassSlabTransmitsBeerLambertAndFresnel): the channel's draw is unbiased.
TEST(LayeredRender, DispersiveSlabFollowsOneChannelUnbiased) {
  const Rgb emitted(1.0f, 0.5f, 0.25f);
  const Image im = glass_slab_image(0.5f, 2.0f, emitted, 512);
  const double slab = slab_transmittance(0.5f);
  for (int c = 0; c < 3; ++c) {
    double mean = 0;
    for (int y = 0; y < 8; ++y)
      for (int x = 0; x < 8; ++x) mean += pixel(im, x, y)[c];
    mean /= 64;
    // 64 pixels × 512 paths, each carrying 3× its channel a third of the time: σ/mean ≈ 0.6 %.
    EXPECT_NEAR(mean, emitted[c] * slab, 0.025 * emitted[c] * slab) << "channel " << c;
  }
}

}  // namespace
}  // namespace svbrdf
