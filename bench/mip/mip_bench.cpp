// MIP benchmarks (bench/results/mip.md): BRDF and parameter pyramid builds of the procedural
// presets, and the renderer's per-hit cost — a lookup plus an eval of a `brdf` texel against a
// level-0 `gltf` eval (the texel's frame, the model, the f_eff factor), without and with a clear coat
// or a sheen.
#include <benchmark/benchmark.h>

#include <map>
#include <memory>
#include <string>

#include "appearance/frame.h"
#include "appearance/gltf.h"
#include "appearance/gltf_surface_bsdf.h"
#include "appearance/rng.h"
#include "mip/mip_data.h"
#include "mip/mip_lookup.h"
#include "textures/material_family.h"

namespace svbrdf {
namespace {

const char* const kPresets[] = {"metal-tray", "painted-wall", "printed-paper", "sandstone", "granite"};

const MaterialTexels& material(int preset, int size) {
  static std::map<std::pair<int, int>, MaterialTexels> cache;
  auto it = cache.find({preset, size});
  if (it == cache.end()) {
    MaterialRecipe r;
    r.preset = kPresets[preset];
    r.size = size;
    it = cache.emplace(std::pair{preset, size}, generate_material(r).texels).first;
  }
  return it->second;
}

// The BRDF pyramid build (levels 1.., from the decoded level 0), per preset, size and --lobes.
void BM_BrdfPyramidBuild(benchmark::State& state) {
  const MaterialTexels& m = material(static_cast<int>(state.range(0)), static_cast<int>(state.range(1)));
  BrdfBuildOptions o;
  o.reduction.max_lobes = static_cast<int>(state.range(2));
  for (auto _ : state) {
    BrdfPyramid p = BrdfPyramid::build(m, o);
    benchmark::DoNotOptimize(p);
  }
  state.SetLabel(kPresets[state.range(0)]);
  state.counters["texels/s"] = benchmark::Counter(double(m.size()) * 4 / 3, benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK(BM_BrdfPyramidBuild)
    ->ArgsProduct({{0, 1, 2, 3, 4}, {1024}, {4}})
    ->Args({0, 1024, 1})->Args({0, 1024, 2})->Args({0, 1024, 8})
    ->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_ParamPyramidBuild(benchmark::State& state) {
  const MaterialTexels& m = material(static_cast<int>(state.range(0)), static_cast<int>(state.range(1)));
  for (auto _ : state) {
    ParamPyramid p = ParamPyramid::build(m);
    benchmark::DoNotOptimize(p);
  }
}
BENCHMARK(BM_ParamPyramidBuild)->Args({0, 1024})->Unit(benchmark::kMillisecond)->UseRealTime();

// Random hits: uv, a footprint of 1–64 texels (so every level gets used), directions above the horizon.
struct Hit {
  Footprint f;
  float u;
  glm::vec3 wi, wo;
};
std::vector<Hit> hits(int n, int size, float max_texels) {
  Rng rng(7, 1);
  std::vector<Hit> out(static_cast<std::size_t>(n));
  for (Hit& h : out) {
    const float w = std::exp2(rng.next_float() * std::log2(max_texels)) / static_cast<float>(size);
    h.f = {{rng.next_float(), rng.next_float()}, {w, 0.2f * w * rng.next_float()}, {0.1f * w, w * (0.5f + rng.next_float())}};
    h.u = rng.next_float();
    auto dir = [&] {
      const float z = 0.1f + 0.9f * rng.next_float(), phi = 6.2831853f * rng.next_float(), s = std::sqrt(1 - z * z);
      return glm::vec3(s * std::cos(phi), s * std::sin(phi), z);
    };
    h.wi = dir();
    h.wo = dir();
  }
  return out;
}

const MipData& tray_mip(int lobes) {
  static std::map<int, std::unique_ptr<MipData>> cache;
  auto& p = cache[lobes];
  if (!p) {
    BrdfBuildOptions o;
    o.reduction.max_lobes = lobes;
    p = std::make_unique<MipData>(build_mip(material(0, 1024), o));
  }
  return *p;
}

// Lookup (footprint → taps → one texel, copied into a LobeMixtureBsdf) + eval. Footprints 1–`max_texels` texels.
void lookup_eval(benchmark::State& state, const MipData& mip, float max_texels) {
  const std::vector<Hit> hs = hits(4096, 1024, max_texels);
  std::size_t k = 0;
  for (auto _ : state) {
    const Hit& h = hs[k++ & 4095];
    const LobeMixtureBsdf b = lookup_brdf(mip, h.f, h.u);
    benchmark::DoNotOptimize(b.eval(h.wi, h.wo));
  }
}
void BM_LookupEvalBrdf(benchmark::State& state) {
  lookup_eval(state, tray_mip(static_cast<int>(state.range(0))), static_cast<float>(state.range(1)));
}
BENCHMARK(BM_LookupEvalBrdf)->ArgsProduct({{1, 2, 4, 8}, {64}})->Args({4, 1})->Args({4, 4});

// The 1024² tray with a layer on top, `add` setting its factors.
template <class Layer>
MipData tray_with(const Layer& add) {
  MaterialTexels m = material(0, 1024);
  add(m);
  return build_mip(std::move(m));
}

// The same on the tray under a clear coat (weight 1, roughness 0.1, no coat normal map: car paint's
// coat): the texel's base lobes with their coat shares and its coat lobes, the layered eval.
const MipData& coated_tray_mip() {
  static const MipData mip = tray_with([](MaterialTexels& m) {
    m.clearcoat_factor = 1.0f;
    m.clearcoat_roughness_factor = 0.1f;
  });
  return mip;
}
void BM_LookupEvalBrdfCoated(benchmark::State& state) {
  lookup_eval(state, coated_tray_mip(), static_cast<float>(state.range(0)));
}
BENCHMARK(BM_LookupEvalBrdfCoated)->Arg(64);

// The same on the tray under a sheen (colour 0.5, roughness 0.5 everywhere): the texel's base lobes with
// their sheen shares and the texel's sheen means, the sheen taken over each lobe's spread normals.
const MipData& sheen_tray_mip() {
  static const MipData mip = tray_with([](MaterialTexels& m) {
    m.sheen_color_factor = glm::vec3(0.5f);
    m.sheen_roughness_factor = 0.5f;
  });
  return mip;
}
void BM_LookupEvalBrdfSheen(benchmark::State& state) {
  lookup_eval(state, sheen_tray_mip(), static_cast<float>(state.range(0)));
}
BENCHMARK(BM_LookupEvalBrdfSheen)->Arg(64);

// The same texel's mixture evaluated again (what the integrator does for light samples), without the
// lookup's cache misses: 64 texels of level state.range(0), each as `texel(mip, level, i, j)` makes it.
template <class Texel>
void eval_texels(benchmark::State& state, const MipData& mip, const Texel& texel) {
  const std::vector<Hit> hs = hits(4096, 1024, 64);
  const int level = static_cast<int>(state.range(0));
  const Extent e = mip.extent(level);
  std::vector<LobeMixtureBsdf> texels;
  for (int t = 0; t < 64; ++t) texels.push_back(texel(mip, level, (t * 37) % e.width, (t * 11) % e.height));
  // One eval before the clock: the first sheen eval builds the sheen's albedo table (appearance/sheen.h).
  benchmark::DoNotOptimize(texels[0].eval(hs[0].wi, hs[0].wo));
  std::size_t k = 0;
  for (auto _ : state) {
    const Hit& h = hs[k & 4095];
    benchmark::DoNotOptimize(texels[k++ & 63].eval(h.wi, h.wo));
  }
}

void BM_EvalBrdfTexel(benchmark::State& state) {
  eval_texels(state, tray_mip(4), [](const MipData& mip, int level, int i, int j) {
    Lobe scratch;
    return LobeMixtureBsdf(brdf_texel(mip, level, i, j, scratch));
  });
}
BENCHMARK(BM_EvalBrdfTexel)->Arg(0)->Arg(3)->Arg(6);

// The coated tray's layered eval.
void BM_EvalBrdfTexelCoated(benchmark::State& state) {
  eval_texels(state, coated_tray_mip(), [](const MipData& mip, int level, int i, int j) {
    Lobe scratch, coat_scratch;
    return LobeMixtureBsdf(brdf_texel(mip, level, i, j, scratch), brdf_coat(mip, level, i, j, coat_scratch).lobes);
  });
}
BENCHMARK(BM_EvalBrdfTexelCoated)->Arg(0)->Arg(3)->Arg(6);

// The sheen tray's: the texel's lobes under its sheen, each lobe's sheen over its spread normals.
void BM_EvalBrdfTexelSheen(benchmark::State& state) {
  eval_texels(state, sheen_tray_mip(), [](const MipData& mip, int level, int i, int j) {
    Lobe scratch;
    LobeMixtureBsdf b(brdf_texel(mip, level, i, j, scratch));
    b.set_sheen(*brdf_sheen(mip, level, i, j));
    return b;
  });
}
BENCHMARK(BM_EvalBrdfTexelSheen)->Arg(0)->Arg(3)->Arg(6);

// Level 0 as the renderer would shade it: the hit's texel of the 1024² tray, the texel's frame, the
// model `eval(t, local wi, local wo)` in it, the f_eff factor max(0, n·wi)/wi.z.
template <class Eval>
void level0_eval(benchmark::State& state, const Eval& eval) {
  const MaterialTexels& m = material(0, 1024);
  const std::vector<Hit> hs = hits(4096, 1024, 1);
  std::size_t k = 0;
  for (auto _ : state) {
    const Hit& h = hs[k++ & 4095];
    const int i = static_cast<int>(h.f.uv.x * 1024), j = static_cast<int>(h.f.uv.y * 1024);
    const std::size_t t = m.index(i, j);
    const glm::vec3 n = m.normal[t];
    const Frame fr = Frame::from_normal(n);
    const float cn = glm::dot(n, h.wi);
    Rgb f(0);
    if (cn > 0) f = eval(m, t, fr, fr.to_local(h.wi), fr.to_local(h.wo)) * (cn / h.wi.z);
    benchmark::DoNotOptimize(f);
  }
}

// With the glTF model.
void BM_Level0GltfEval(benchmark::State& state) {
  level0_eval(state, [](const MaterialTexels& m, std::size_t t, const Frame&, const glm::vec3& wi, const glm::vec3& wo) {
    return gltf_eval({m.base_color[t], m.metallic[t], m.roughness[t]}, wi, wo);
  });
}
BENCHMARK(BM_Level0GltfEval);

// With the surface BSDF under the coated tray's coat (fresnel_coat; the coat normal the surface's,
// carried into the texel's frame): the coated level 0 as the renderer shades it.
void BM_Level0CoatedEval(benchmark::State& state) {
  level0_eval(state, [](const MaterialTexels& m, std::size_t t, const Frame& fr, const glm::vec3& wi, const glm::vec3& wo) {
    ShadingParams p;
    p.base_color = m.base_color[t], p.metallic = m.metallic[t], p.roughness = m.roughness[t];
    p.clearcoat = 1.0f, p.clearcoat_roughness = 0.1f, p.clearcoat_normal = fr.to_local(glm::vec3(0, 0, 1));
    return SurfaceBsdf(p).eval(wi, wo);
  });
}
BENCHMARK(BM_Level0CoatedEval);

// With the surface BSDF under the sheen tray's sheen: the sheened level 0 as the renderer shades it.
void BM_Level0SheenEval(benchmark::State& state) {
  level0_eval(state, [](const MaterialTexels& m, std::size_t t, const Frame&, const glm::vec3& wi, const glm::vec3& wo) {
    ShadingParams p;
    p.base_color = m.base_color[t], p.metallic = m.metallic[t], p.roughness = m.roughness[t];
    p.sheen_color = Rgb(0.5f), p.sheen_roughness = 0.5f;
    return SurfaceBsdf(p).eval(wi, wo);
  });
}
BENCHMARK(BM_Level0SheenEval);

// The bare model on fixed parameters in its own frame: no texel fetch, no frame, no f_eff factor.
void BM_GltfEvalOnly(benchmark::State& state) {
  const std::vector<Hit> hs = hits(4096, 1024, 1);
  const GltfParams p{Rgb(0.9f, 0.9f, 0.88f), 1.0f, 0.2f};
  std::size_t k = 0;
  for (auto _ : state) {
    const Hit& h = hs[k++ & 4095];
    benchmark::DoNotOptimize(gltf_eval(p, h.wi, h.wo));
  }
}
BENCHMARK(BM_GltfEvalOnly);

}  // namespace
}  // namespace svbrdf
