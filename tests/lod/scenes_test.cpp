// The scenes the build bakes (svbrdf-bake scene on scenes/*.json): valid glTF by the Khronos
// validator, byte-identical bakes, one-line errors for bad input, cameras at the distances the
// formula of scenes/lod_scenes.h promises (measured with the renderer's own camera model), quads
// that fill every LOD image, a proxy normal map that holds the roof's normals, and a showcase
// camera that sees the near tray and the far wall.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <map>
#include <numbers>
#include <string>
#include <vector>

#include "render/camera.h"
#include "gltf/scene_reader.h"
#include "render/render_setup.h"
#include "scenes/lod_scenes.h"
#include "scenes/recipe.h"
#include "textures/image.h"
#include "textures/normal_map.h"
#include "tests/common/run_command.h"
#include "tests/common/test_paths.h"

namespace svbrdf {
namespace {

namespace fs = std::filesystem;
using testing::run_command;
using testing::slurp;
using testing::TempDir;

const fs::path kSource = SVBRDF_SOURCE_DIR;
const fs::path kScenes = fs::path(SVBRDF_BINARY_DIR) / "scenes";
const std::string kBake = SVBRDF_BAKE;

std::vector<fs::path> built_gltfs() {
  std::vector<fs::path> out{kScenes / "showcase" / "showcase.gltf"};
  for (const auto& e : fs::recursive_directory_iterator(kScenes / "lod"))
    if (e.path().extension() == ".gltf") out.push_back(e.path());
  std::sort(out.begin() + 1, out.end());
  return out;
}

TEST(Scenes, BuiltScenesPassTheKhronosValidator) {
  const fs::path validator = kSource / "tools/node_modules/gltf-validator";
  const fs::path script = kSource / "tests/textures/validate_gltf.cjs";
  if (std::system("node --version >/dev/null 2>&1") != 0)
    GTEST_SKIP() << "node is not installed: cannot run the Khronos glTF validator (tools/install-deps installs it with npm)";
  if (!fs::exists(validator / "package.json"))
    GTEST_SKIP() << "gltf-validator is not in " << validator << ": run tools/install-deps (needs npm)";
  const auto files = built_gltfs();
  ASSERT_GE(files.size(), 8u);  // showcase, five families, the roof and its proxy
  std::string command = "node '" + script.string() + "' '" + validator.string() + "'";
  for (const auto& f : files) command += " '" + f.string() + "'";
  const TempDir dir;
  const auto r = run_command(command, dir.path());
  EXPECT_EQ(r.status, 0) << r.err;
  std::vector<std::string> lines;
  std::size_t start = 0;
  for (std::size_t nl; (nl = r.out.find('\n', start)) != std::string::npos; start = nl + 1)
    lines.push_back(r.out.substr(start, nl - start));
  ASSERT_EQ(lines.size(), files.size()) << r.out << r.err;
  for (std::size_t k = 0; k < files.size(); ++k) {
    EXPECT_NE(lines[k].find(files[k].string()), std::string::npos) << lines[k];
    EXPECT_NE(lines[k].find("\"errors\":0,\"warnings\":0,"), std::string::npos) << lines[k];
  }
}

TEST(Scenes, BakesAreByteIdentical) {
  const TempDir dir;
  for (const char* run : {"a", "b"}) {
    const auto r = run_command(kBake + " scene '" + (kSource / "scenes/lod.json").string() + "' --out '" +
                                   (dir / run).string() + "' --quiet",
                               dir.path());
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(r.out, "");
  }
  int files = 0;
  for (const auto& e : fs::recursive_directory_iterator(dir / "a")) {
    if (!e.is_regular_file()) continue;
    const fs::path other = dir / "b" / fs::relative(e.path(), dir / "a");
    ASSERT_TRUE(fs::exists(other)) << other;
    EXPECT_TRUE(slurp(e.path()) == slurp(other)) << e.path() << " differs between two bakes";
    ++files;
  }
  EXPECT_GE(files, 20);
}

TEST(Scenes, BadInputIsOneLineExitTwoAndNothingWritten) {
  const TempDir dir;
  const auto write = [&](const std::string& name, const std::string& text) {
    std::FILE* f = std::fopen((dir / name).c_str(), "w");
    std::fputs(text.c_str(), f);
    std::fclose(f);
    return (dir / name).string();
  };
  const std::string typo = write("typo.json", "{\"kind\": \"lod\", \"name\": \"x\",\n \"lights\": [], \"famlies\": []}");
  const std::string syntax = write("syntax.json", "{\"kind\": \"lod\",\n\n \"name\": }");
  const std::string good = write("good.json", R"({"kind": "lod", "name": "l", "image_size": 8, "distances": [1, 16],
    "texture_size": 16, "families": [{"material": {"preset": "printed-paper"}}],
    "lights": [{"name": "s", "incidence_deg": 30}]})");
  write("file", "x");
  struct Case {
    std::string args, expect;
  };
  for (const Case& c : std::vector<Case>{
           {"scene " + (dir / "none.json").string(), "none.json: cannot open the file"},
           {"scene " + typo, "typo.json:2: famlies: unknown member"},
           {"scene " + syntax, "syntax.json:3:10: syntax error while parsing value - unexpected '}'"},
           {"scene " + write("preset.json", R"({"kind": "lod", "name": "l", "families": [{"material": {"preset": "slate"}}],
             "lights": [{"name": "s", "incidence_deg": 0}]})"), "preset.json:1: families[0].material.preset: unknown preset \"slate\""},
       }) {
    const auto r = run_command(kBake + " " + c.args + " --out '" + (dir / "out").string() + "'", dir.path());
    EXPECT_EQ(r.status, 2) << c.args << ": " << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_NE(r.err.find(c.expect), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(dir / "out")) << c.args;
  }
  const auto r = run_command(kBake + " scene " + good + " --out '" + (dir / "file").string() + "'", dir.path());
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_NE(r.err.find((dir / "file").string()), std::string::npos) << r.err;
  EXPECT_EQ(slurp(dir / "file"), "x");
  // And the good recipe bakes, listing the manifest first.
  const auto ok = run_command(kBake + " scene " + good + " --out '" + (dir / "ok").string() + "'", dir.path());
  EXPECT_EQ(ok.status, 0) << ok.err;
  EXPECT_EQ(ok.out.substr(0, ok.out.find('\n')), (dir / "ok" / "manifest.json").string());
}

// Where the ray through film position (x, y) meets the plane z = 0.
glm::dvec3 hit_plane(const Camera& cam, float x, float y) {
  const Ray r = cam.ray(x, y);
  const double t = -double(r.origin.z) / double(r.dir.z);
  return glm::dvec3(r.origin) + t * glm::dvec3(r.dir);
}

// One pixel at the image centre covers k texels at k × d₁: measured with the renderer's camera.
TEST(Scenes, LodCamerasSeeKTexelsPerPixel) {
  const LodManifest m = read_lod_manifest(kScenes / "lod" / "manifest.json");
  const int H = m.image_size;
  ASSERT_FALSE(m.cases.empty());
  for (const LodCase& c : m.cases) {
    EXPECT_NEAR(c.one_texel_per_pixel_m, c.texel_m * H / (2 * std::tan(m.yfov_deg * std::numbers::pi / 360)), 1e-12);
    const Scene scene = load_gltf(c.gltf);
    std::map<std::string, const CameraDesc*> cams;
    for (const CameraDesc& d : scene.cameras) cams[d.name] = &d;
    for (const LodView& v : c.views)
      for (std::size_t i = 0; i < v.cameras.size(); ++i) {
        ASSERT_TRUE(cams.count(v.cameras[i])) << c.name << " has no camera " << v.cameras[i];
        const Camera cam(*cams[v.cameras[i]], H, H);
        const float x = H / 2.0f, y = H / 2.0f;
        const double du = glm::length(hit_plane(cam, x + 0.5f, y) - hit_plane(cam, x - 0.5f, y));
        const double dv = glm::length(hit_plane(cam, x, y + 0.5f) - hit_plane(cam, x, y - 0.5f));
        const double k = m.distances[i];
        SCOPED_TRACE(c.name + " " + v.cameras[i]);
        if (v.name == "mirror") {
          // Tilted by the light's incidence about y: the footprint stretches by 1/cos along x.
          const double cos_t = std::cos(m.light(v.lights.front()).incidence_deg * std::numbers::pi / 180);
          EXPECT_NEAR(du / (k * c.texel_m), 1.0 / cos_t, 0.01 / cos_t);
          EXPECT_NEAR(dv / (k * c.texel_m), 1.0, 0.01);
        } else {
          EXPECT_NEAR(du / (k * c.texel_m), 1.0, 0.01);
          EXPECT_NEAR(dv / (k * c.texel_m), 1.0, 0.01);
        }
      }
  }
}

// Every pixel of every LOD image is an object pixel: the image corners land on the quad (and on
// the roof), well inside its edges.
TEST(Scenes, LodQuadsFillEveryImage) {
  const LodManifest m = read_lod_manifest(kScenes / "lod" / "manifest.json");
  for (const LodCase& c : m.cases)
    for (const fs::path& file : {c.gltf, c.reference}) {
      const Scene scene = load_gltf(file);
      glm::dvec3 lo(1e30), hi(-1e30);
      for (const Mesh& mesh : scene.meshes)
        for (const MeshPrimitive& p : mesh.primitives)
          for (const glm::vec3& q : p.positions) lo = glm::min(lo, glm::dvec3(q)), hi = glm::max(hi, glm::dvec3(q));
      for (const CameraDesc& d : scene.cameras) {
        const Camera cam(d, m.image_size, m.image_size);
        for (float x : {0.0f, float(m.image_size)})
          for (float y : {0.0f, float(m.image_size)}) {
            const glm::dvec3 p = hit_plane(cam, x, y);
            EXPECT_TRUE(p.x > lo.x && p.x < hi.x && p.y > lo.y && p.y < hi.y)
                << file.filename() << " camera " << d.name << " corner (" << x << ", " << y << ") misses the object";
          }
      }
    }
}

// The proxy's normal map holds the roof mesh's shading normals at its texel centres: decoded as the
// spec decodes normal maps, it equals the interpolated vertex normals of the geometry file.
TEST(Scenes, TileRoofProxyNormalMapHoldsTheRoofNormals) {
  const LodManifest m = read_lod_manifest(kScenes / "lod" / "manifest.json");
  const LodCase* roof = nullptr;
  for (const LodCase& c : m.cases)
    if (c.kind == "tile-roof") roof = &c;
  ASSERT_NE(roof, nullptr);
  const Scene geometry = load_gltf(roof->reference);
  ASSERT_EQ(geometry.meshes.size(), 1u);
  const MeshPrimitive& p = geometry.meshes[0].primitives.at(0);
  // The vertex normals by x (each column has two vertices, y = ±W/2).
  std::vector<std::pair<double, glm::dvec3>> columns;
  for (std::size_t i = 0; i < p.positions.size(); i += 2) columns.push_back({p.positions[i].x, glm::dvec3(p.normals[i])});
  ASSERT_TRUE(std::is_sorted(columns.begin(), columns.end(), [](auto& a, auto& b) { return a.first < b.first; }));
  const Scene proxy = load_gltf(roof->gltf);
  ASSERT_EQ(proxy.images.size(), 1u);
  const Image& nm = proxy.images[0].pixels;
  ASSERT_EQ(nm.width, roof->texture_size);
  // The proxy quad starts where the roof starts, at a crest (periods is even, so x = 0 is a crest
  // too and begins a texture repeat). Compared near x = 0, where single-precision positions resolve
  // a strip to 1e-7 of its width (at the far ends of a roof hundreds of metres long they do not,
  // for the renderer either).
  const double side = roof->texture_size * roof->texel_m, phase = std::fmod(-columns.front().first, side);
  EXPECT_LT(std::min(phase, side - phase), 1e-3);
  double worst = 0.0;
  for (int rep = -1; rep < 2; ++rep)  // three repeats of the texture around the centre
    for (int i = 0; i < nm.width; ++i) {
      const double x = (rep * nm.width + i + 0.5) * roof->texel_m;
      const auto hi = std::upper_bound(columns.begin(), columns.end(), x, [](double v, auto& c) { return v < c.first; });
      const auto lo = hi - 1;
      const double t = (x - lo->first) / (hi->first - lo->first);
      const glm::dvec3 want = glm::normalize((1 - t) * lo->second + t * hi->second);
      for (int j : {0, nm.height / 2, nm.height - 1}) {
        const glm::dvec3 got = decode_normal(glm::vec3(nm.at(i, j, 0), nm.at(i, j, 1), nm.at(i, j, 2)));
        worst = std::max(worst, glm::length(got - want));
      }
    }
  EXPECT_LT(worst, 1e-4);  // 16-bit quantization (2/65535 per component), single-precision positions
}

// The showcase camera sees every copy of every material, each filling about as many pixels (the
// copies are scaled with their distance: tests/lod/recipe_test.cpp).
TEST(Scenes, ShowcaseCameraSeesEveryCopy) {
  const Scene scene = load_gltf(kScenes / "showcase" / "showcase.gltf");
  ASSERT_EQ(scene.lights.size(), 1u);
  EXPECT_EQ(scene.lights[0].type, LightDesc::Type::directional);
  ASSERT_EQ(scene.cameras.size(), 1u);
  EXPECT_TRUE(fs::exists(kScenes / "showcase" / "sky.hdr"));
  SceneSetup setup;
  setup.width = 160, setup.height = 90;
  const PreparedScene prepared(scene, setup);
  std::map<int, int> pixels;  // by Scene::instances index
  for (int y = 0; y < setup.height; ++y)
    for (int x = 0; x < setup.width; ++x) {
      const Ray r = prepared.camera().ray(x + 0.5f, y + 0.5f);
      const RayHit h = prepared.bvh().intersect(r.origin, r.dir, 0.0f, 1e30f, 0);
      if (h.found()) ++pixels[h.instance];
    }
  ASSERT_EQ(scene.instances.size(), 8u);
  const double n = setup.width * setup.height;
  int smallest = int(n), largest = 0;
  for (int k = 0; k < int(scene.instances.size()); ++k) {
    SCOPED_TRACE(scene.meshes[std::size_t(scene.instances[std::size_t(k)].mesh)].name);
    EXPECT_GT(pixels[k] / n, 0.03);
    smallest = std::min(smallest, pixels[k]), largest = std::max(largest, pixels[k]);
  }
  EXPECT_LT(largest, 1.3 * smallest);
}

// `svbrdf-render` with no scene renders the showcase under its sun and the sky baked beside it (glTF
// carries no environment): the sky is what the camera sees above the copies — bluish, as the recipe's
// gradient (zenith 0.02, 0.03, 0.06; horizon 0.05, 0.05, 0.06) says.
TEST(Scenes, DefaultRenderIsTheShowcaseUnderItsSky) {
  testing::TempDir dir;
  const auto out = dir / "showcase.exr";
  const auto r = run_command(std::string(SVBRDF_RENDER) + " --res 64x36 --spp 4 --quiet --out '" + out.string() + "'",
                             dir.path());
  ASSERT_EQ(r.status, 0) << r.err;
  const Image img = read_image(out);
  ASSERT_EQ(img.width, 64);
  // The top-left pixel: sky, left of and above the copies, between the horizon's and the zenith's blue.
  EXPECT_GT(img.at(0, 0, 2), 0.05f);
  EXPECT_LT(img.at(0, 0, 2), 0.065f);
  EXPECT_GT(img.at(0, 0, 2), img.at(0, 0, 0));  // blue over red
}

// At k × d₁ a pixel of the manifest's image size covers k texels across (lod_scenes.h), and each of
// a render's spp camera samples filters its share of the pixel, 1/√spp of it unless --footprint-scale
// says otherwise (render/renderer.h): the MIP-level AOV at 16 × d₁ reads log₂(16 · scale) — 4 at a
// scale of 1, 3 at 4 spp by default (1/2), 2 at 16 spp (1/4), 0 at 256 spp (1/16; pbrt-v4's floor of
// 1/8 would read 1).
TEST(Scenes, LodCameraReadsTheLevelOfItsDistanceAndFootprintScale) {
  testing::TempDir dir;
  const auto out = dir / "d16.exr";
  const fs::path scene = kScenes / "lod" / "printed-paper-text" / "printed-paper-text.gltf";
  const int size = read_lod_manifest(kScenes / "lod" / "manifest.json").image_size;
  const std::string res = std::to_string(size) + "x" + std::to_string(size);
  struct Case {
    std::string args;
    float level;
  };
  for (const Case& c : {Case{"--spp 4 --footprint-scale 1", 4.0f}, Case{"--spp 4", 3.0f}, Case{"--spp 16", 2.0f},
                        Case{"--spp 256", 0.0f}, Case{"--spp 1 --footprint-scale 0.125", 1.0f}}) {
    const auto r = run_command(std::string(SVBRDF_RENDER) + " '" + scene.string() + "' --camera d16 --res " + res + " --float --aov " +
                                   c.args + " --quiet --out '" + out.string() + "'",
                               dir.path());
    ASSERT_EQ(r.status, 0) << c.args << ": " << r.err;
    const Image level = read_image_channels(out, {"mip_level.X"});
    for (const auto& [x, y] : {std::pair{0, 0}, std::pair{size / 2, size / 2}, std::pair{size - 1, 2}})
      EXPECT_NEAR(level.at(x, y, 0), c.level, 0.05f) << c.args << " at pixel " << x << "," << y;
  }
  for (const char* bad : {"0", "-1", "x"}) {
    const auto r = run_command(std::string(SVBRDF_RENDER) + " '" + scene.string() + "' --footprint-scale " + bad +
                                   " --quiet --out '" + out.string() + "'",
                               dir.path());
    EXPECT_EQ(r.status, 2) << "--footprint-scale " << bad << ": " << r.err;
  }
}

}  // namespace
}  // namespace svbrdf
