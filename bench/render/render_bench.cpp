// The renderer benchmark: rays per second of the whole renderer on a textured scene
// (DamagedHelmet at 640×360, 64 spp) against raw Embree on the same rays in the same run, at 1 and 2
// threads, under --filter level0 and brdf (the default); time per frame, setup and MIP build times,
// and peak memory. The raw side replays the renderer's own rays — recorded
// from the same frame at 8 spp (the same pixels, paths and ray mix; 1/8 of the count) and traced 8
// times, so both sides trace the same number of rays — with rtcIntersect1 for closest-hit rays and
// rtcOccluded1 for shadow rays, through the same Embree scene (filters included).
//
// ShowcaseUntextured is the showcase with every texture slot emptied and one constant rough
// dielectric material (gray, roughness 1, metallic 0): the same geometry, lights, sky and paths with
// the cheapest surface the renderer shades. Its ratio is the ceiling that no texture filter can
// raise the textured showcase above — what the integrator itself (NEE to the sun and the sky, MIS,
// the sky's importance sampling) costs against a BVH of a few hundred triangles.
//
// LayeredMaterials: what the glTF extension layers cost a whole frame. One scene built in code — a
// floor and six spheres under a directional light and a uniform sky — rendered twice in each
// iteration, with the same seed, size and samples: the spheres wearing the base material, then
// each wearing one layer (clearcoat, anisotropy, sheen, iridescence, transmission into a volume,
// and the base). Texture filter level0, so both frames shade every material with SurfaceBsdf.
#include <benchmark/benchmark.h>

#include <chrono>
#include <filesystem>
#include <map>
#include <memory>
#include <sys/resource.h>

#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "gltf/scene_reader.h"
#include "mip/texture_filter.h"
#include "render/ray_log.h"
#include "render/render_setup.h"
#include "render/renderer.h"
#include "tests/render/render_test_scenes.h"

namespace svbrdf {
namespace {

namespace fs = std::filesystem;

double peak_rss_mb() {
  rusage r{};
  getrusage(RUSAGE_SELF, &r);
  return double(r.ru_maxrss) / 1024.0;  // kilobytes on Linux
}

struct Loaded {
  std::unique_ptr<PreparedScene> scene;
  std::map<TextureFilter, std::vector<RecordedRay>> rays;  // per filter, the 8-spp frame's rays
  double setup_seconds = 0.0;                              // load_gltf + PreparedScene (textures, BVH)
};

// Every material of `scene` made one constant rough gray dielectric with no texture.
void strip_textures(Scene& scene) {
  for (MaterialDesc& m : scene.materials) {
    m.base_color_texture = m.metallic_roughness_texture = m.normal_texture = m.occlusion_texture = TextureRef{};
    m.emissive_texture = m.specular_texture = m.specular_color_texture = TextureRef{};
    m.transmission_texture = m.diffuse_roughness_texture = TextureRef{};
    m.base_color = Rgb(0.5f);
    m.metallic = 0.0f;
    m.roughness = 1.0f;
  }
}

// Loads a scene once per process (per file and `untextured`); null when the file is absent.
// `env`: SceneSetup::env (empty: the renderer's default).
Loaded* load(const fs::path& file, int width, int height, bool untextured = false, const std::string& env = "") {
  static std::map<std::string, std::unique_ptr<Loaded>> cache;
  const std::string key = file.string() + (untextured ? "#untextured" : "");
  auto it = cache.find(key);
  if (it != cache.end()) return it->second.get();
  if (!fs::exists(file)) return nullptr;
  auto l = std::make_unique<Loaded>();
  SceneSetup setup;
  setup.width = width, setup.height = height;
  setup.env = env;
  const auto t0 = std::chrono::steady_clock::now();
  Scene scene = load_gltf(file);
  if (untextured) strip_textures(scene);
  l->scene = std::make_unique<PreparedScene>(std::move(scene), setup);
  l->setup_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return cache.emplace(key, std::move(l)).first->second.get();
}

// The renderer's own rays of an 8-spp frame under `filter` (the same pixels, paths and ray mix as
// the timed frame), recorded once per filter.
const std::vector<RecordedRay>& recorded_rays(Loaded& l, TextureFilter filter) {
  auto it = l.rays.find(filter);
  if (it != l.rays.end()) return it->second;
  RayLog log;
  RenderWorld world = l.scene->world();
  world.ray_log = &log;
  RenderOptions o;
  o.spp = 8;
  o.integrator.filter = filter;
  o.integrator.footprints = false;
  // The timed frame's footprints: its spp's scale, not the 8-spp frame's.
  o.integrator.footprint_scale = 0.125f;
  render(world, o);
  return l.rays.emplace(filter, log.gather()).first->second;
}

double raw_embree_seconds(const EmbreeScene& bvh, const std::vector<RecordedRay>& rays, int repeats, int threads) {
  tbb::task_arena arena(threads);
  const auto t0 = std::chrono::steady_clock::now();
  arena.execute([&] {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, rays.size(), 4096), [&](const tbb::blocked_range<std::size_t>& r) {
      set_denormals_zero();
      std::size_t hits = 0;
      for (int rep = 0; rep < repeats; ++rep)
        for (std::size_t i = r.begin(); i < r.end(); ++i) {
          const RecordedRay& ray = rays[i];
          if (ray.shadow) hits += bvh.occluded(ray.origin, ray.dir, ray.tnear, ray.tfar, ray.seed);
          else hits += bvh.intersect(ray.origin, ray.dir, ray.tnear, ray.tfar, ray.seed).found();
        }
      benchmark::DoNotOptimize(hits);
    });
  });
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

void bench_scene(benchmark::State& state, const fs::path& file, bool untextured = false, const std::string& env = "") {
  const int threads = int(state.range(0));
  const TextureFilter filter = TextureFilter(state.range(1));
  constexpr int kWidth = 640, kHeight = 360, kSpp = 64, kRecordedSpp = 8;
  Loaded* l = load(file, kWidth, kHeight, untextured, env);
  if (!l) {
    state.SkipWithError(("scene not found: " + file.string()).c_str());
    for (auto _ : state) {
    }
    return;
  }
  // The MIP data of the filter, built before the clock starts (as svbrdf-render builds it at setup).
  const auto t0 = std::chrono::steady_clock::now();
  l->scene->world().mips->prepare(filter);
  const double mip_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const std::vector<RecordedRay>& rays = recorded_rays(*l, filter);
  RenderOptions o;
  o.spp = kSpp;
  o.threads = threads;
  o.integrator.filter = filter;
  o.integrator.footprints = false;  // as svbrdf-render runs without --aov
  o.aovs = false;
  RenderStats stats;
  double raw_seconds = 0.0;
  for (auto _ : state) {
    render(l->scene->world(), o, &stats);
    raw_seconds = raw_embree_seconds(l->scene->bvh(), rays, kSpp / kRecordedSpp, threads);
    state.SetIterationTime(stats.seconds);
  }
  const double raw_rays = double(rays.size()) * (kSpp / kRecordedSpp);
  const double renderer_mrays = double(stats.rays) / stats.seconds * 1e-6;
  const double raw_mrays = raw_rays / raw_seconds * 1e-6;
  state.counters["frame_s"] = stats.seconds;
  state.counters["rays_M"] = double(stats.rays) * 1e-6;
  state.counters["raw_rays_M"] = raw_rays * 1e-6;
  state.counters["render_Mrays/s"] = renderer_mrays;
  state.counters["raw_Mrays/s"] = raw_mrays;
  state.counters["ratio"] = renderer_mrays / raw_mrays;
  state.counters["peak_MB"] = peak_rss_mb();
  state.counters["setup_s"] = l->setup_seconds;
  state.counters["mip_build_s"] = mip_seconds;  // 0 when an earlier run built it
  state.SetLabel(std::string(filter_name(filter)));
}

void BM_DamagedHelmet(benchmark::State& state) {
  // Under the white sky of radiance 1 its figures were always measured under: a scene with emissive
  // surfaces no longer gets it by default.
  bench_scene(state, fs::path(SVBRDF_SHARED_DIR) / "data/gltf-samples/DamagedHelmet/glTF/DamagedHelmet.gltf", false, "1");
}
void BM_Showcase(benchmark::State& state) {
  bench_scene(state, fs::path(SVBRDF_BINARY_DIR) / "scenes/showcase/showcase.gltf");
}

void BM_ShowcaseUntextured(benchmark::State& state) {
  bench_scene(state, fs::path(SVBRDF_BINARY_DIR) / "scenes/showcase/showcase.gltf", true);
}

// The LayeredMaterials scene: a 12 m floor (material 0) and six unit spheres 2.4 m apart in a row;
// sphere i wears material 1 + i, or material 1 (the base) when not `layered`.
Scene layered_scene(bool layered) {
  Scene s;
  s.materials.push_back(test::lambertian(Rgb(0.5f)));
  MaterialDesc base;
  base.base_color = Rgb(0.8f, 0.3f, 0.2f);
  base.metallic = 0.0f;
  base.roughness = 0.5f;
  std::vector<MaterialDesc> spheres(6, base);
  spheres[1].clearcoat = 1.0f, spheres[1].clearcoat_roughness = 0.1f;
  spheres[2].anisotropy_strength = 0.6f;
  spheres[3].sheen_color = Rgb(0.9f, 0.6f, 0.3f), spheres[3].sheen_roughness = 0.5f;
  spheres[4].iridescence = 1.0f;
  spheres[5].transmission = 1.0f, spheres[5].thickness = 1.0f;
  spheres[5].attenuation_distance = 1.0f, spheres[5].attenuation_color = Rgb(0.9f, 0.6f, 0.3f);
  for (std::size_t i = 0; i < spheres.size(); ++i) s.materials.push_back(layered ? spheres[i] : base);
  test::add_quad(s, 0, glm::rotate(glm::dmat4(1.0), -1.5707963267948966, glm::dvec3(1, 0, 0)), 12.0f);
  for (int i = 0; i < 6; ++i) {
    test::add_sphere(s, 1 + i, 1.0f, 24, 48);
    s.instances.back().to_world = glm::translate(glm::dmat4(1.0), glm::dvec3(2.4 * (i - 2.5), 1.0, 0.0));
  }
  s.cameras.push_back(test::perspective_camera({0, 3.5, 9}, {0, 0.8, 0}, 40.0f));
  LightDesc sun;
  sun.type = LightDesc::Type::directional;
  sun.intensity = 3.0f;
  sun.direction = glm::normalize(glm::vec3(-0.4f, -1.0f, -0.5f));
  s.lights.push_back(sun);
  return s;
}

void BM_LayeredMaterials(benchmark::State& state) {
  constexpr int kWidth = 320, kHeight = 180, kSpp = 16;
  SceneSetup setup;
  setup.width = kWidth, setup.height = kHeight;
  setup.env = "0.5";
  const PreparedScene plain(layered_scene(false), setup), layered(layered_scene(true), setup);
  RenderOptions o;
  o.spp = kSpp;
  o.seed = 1;
  o.threads = int(state.range(0));
  o.integrator.filter = TextureFilter::level0;
  o.integrator.footprints = false;
  o.aovs = false;
  RenderStats ps, ls;
  double plain_total = 0.0, layered_total = 0.0;
  for (auto _ : state) {
    render(plain.world(), o, &ps);
    render(layered.world(), o, &ls);
    plain_total += ps.seconds, layered_total += ls.seconds;
    state.SetIterationTime(ps.seconds + ls.seconds);
  }
  const double n = double(state.iterations());
  state.counters["plain_frame_s"] = plain_total / n;
  state.counters["layered_frame_s"] = layered_total / n;
  state.counters["plain_Msamples/s"] = double(ps.samples) / (plain_total / n) * 1e-6;
  state.counters["layered_Msamples/s"] = double(ls.samples) / (layered_total / n) * 1e-6;
  state.counters["plain_Mrays/s"] = double(ps.rays) / (plain_total / n) * 1e-6;
  state.counters["layered_Mrays/s"] = double(ls.rays) / (layered_total / n) * 1e-6;
  state.counters["time_ratio"] = layered_total / plain_total;
}

// Arguments: threads, filter (TextureFilter: 0 level0, 4 brdf, svbrdf-render's default).
constexpr int kLevel0 = int(TextureFilter::level0), kBrdf = int(TextureFilter::brdf);
BENCHMARK(BM_DamagedHelmet)
    ->Args({1, kLevel0})->Args({2, kLevel0})->Args({1, kBrdf})->Args({2, kBrdf})
    ->ArgNames({"threads", "filter"})->Iterations(1)->UseManualTime()->Unit(benchmark::kSecond);
BENCHMARK(BM_Showcase)
    ->Args({1, kLevel0})->Args({2, kLevel0})->Args({1, kBrdf})->Args({2, kBrdf})
    ->ArgNames({"threads", "filter"})->Iterations(1)->UseManualTime()->Unit(benchmark::kSecond);
BENCHMARK(BM_LayeredMaterials)
    ->Arg(1)->Arg(2)->ArgName("threads")->Iterations(3)->UseManualTime()->Unit(benchmark::kSecond);
BENCHMARK(BM_ShowcaseUntextured)
    ->Args({1, kLevel0})->Args({2, kLevel0})
    ->ArgNames({"threads", "filter"})->Iterations(1)->UseManualTime()->Unit(benchmark::kSecond);

}  // namespace
}  // namespace svbrdf
