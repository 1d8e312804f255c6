// ns per eval and per sample of every model of brdf-models.md (default parameters unless named),
// over 4096 precomputed random direction pairs / random numbers so the branch mix is realistic; eval
// over a batch of 10^6 pairs, the Python module's anchor (eval_batch_bench); and
// of the renderer's glTF surface (SurfaceBsdf) with each extension layer alone, against the same
// material without it in the same run.
#include <benchmark/benchmark.h>

#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "appearance/gltf_bsdf.h"
#include "appearance/gltf_surface_bsdf.h"
#include "appearance/measured.h"
#include "appearance/mixture.h"
#include "appearance/registry.h"
#include "appearance/rng.h"
#include "appearance/sheen.h"
#include "appearance/thin_film.h"

namespace {

using namespace svbrdf;

constexpr std::size_t kN = 4096;

struct Inputs {
  std::vector<glm::vec3> wi, wo;
  std::vector<SampleU> u;
  explicit Inputs(std::size_t n = kN) {
    Rng rng(42, 1);
    auto dir = [&] {
      const float z = 0.02f + 0.98f * rng.next_float(), phi = 6.2831853f * rng.next_float();
      const float r = std::sqrt(1 - z * z);
      return glm::vec3(r * std::cos(phi), r * std::sin(phi), z);
    };
    for (std::size_t i = 0; i < n; ++i) {
      wi.push_back(dir());
      wo.push_back(dir());
      u.push_back({rng.next_float(), rng.next_float(), rng.next_float()});
    }
  }
};
const Inputs& inputs() {
  static const Inputs in;
  return in;
}

void eval_bench(benchmark::State& state, std::shared_ptr<const Bsdf> bsdf) {
  const Inputs& in = inputs();
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(bsdf->eval(in.wi[i], in.wo[i]));
    i = (i + 1) & (kN - 1);
  }
}

// eval over one batch of 10^6 pairs into an array, as a caller evaluating many pairs at once runs it
// (the Python module's Bsdf.eval, bench/python/bsdf_eval.py): the pairs stream from memory and the
// branches meet no repeating sequence, unlike eval/ cycling through 4096. Time per batch; ns per pair
// is that over kBatch.
constexpr std::size_t kBatch = 1000000;

const Inputs& batch_inputs() {
  static const Inputs in(kBatch);
  return in;
}

void eval_batch_bench(benchmark::State& state, std::shared_ptr<const Bsdf> bsdf) {
  const Inputs& in = batch_inputs();
  std::vector<Rgb> out(kBatch);
  for (auto _ : state) {
    for (std::size_t k = 0; k < kBatch; ++k) out[k] = bsdf->eval(in.wi[k], in.wo[k]);
    benchmark::DoNotOptimize(out.data());
    benchmark::ClobberMemory();
  }
  state.counters["pairs"] = double(kBatch);
}

void sample_bench(benchmark::State& state, std::shared_ptr<const Bsdf> bsdf) {
  const Inputs& in = inputs();
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(bsdf->sample(in.wo[i], in.u[i]));
    i = (i + 1) & (kN - 1);
  }
}

void pdf_bench(benchmark::State& state, std::shared_ptr<const Bsdf> bsdf) {
  const Inputs& in = inputs();
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(bsdf->pdf(in.wi[i], in.wo[i]));
    i = (i + 1) & (kN - 1);
  }
}

// The glTF extension building blocks as the surface BSDF calls them, per shading query: the sheen
// albedo scaling (two table lookups) and the thin-film Fresnel at wo·h (random cosines, thickness
// 100–400 nm, the extension's default range, and a metal-like F0).
void sheen_scaling_bench(benchmark::State& state) {
  const Inputs& in = inputs();
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(sheen_albedo_scaling(in.wi[i], in.wo[i], Rgb(0.9f, 0.6f, 0.3f), 0.5f));
    i = (i + 1) & (kN - 1);
  }
}

void thin_film_bench(benchmark::State& state) {
  const Inputs& in = inputs();
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(iridescence_fresnel(in.wo[i].z, 100.0f + 300.0f * in.u[i].x, 1.3f, Rgb(0.9f, 0.6f, 0.3f)));
    i = (i + 1) & (kN - 1);
  }
}

// A two-lobe mixture of gltf lobes on the stack, as the MIP lookup builds per shading point.
class TwoGltfLobes final : public Bsdf {
 public:
  TwoGltfLobes() : a_({Rgb(0.8f, 0.2f, 0.1f), 0.0f, 0.6f}), b_({Rgb(0.9f), 1.0f, 0.15f}) {
    mix_.add(a_, 0.7f);
    mix_.add(b_, 0.3f);
  }
  Rgb eval(const glm::vec3& wi, const glm::vec3& wo) const override { return mix_.eval(wi, wo); }
  BsdfSample sample(const glm::vec3& wo, const SampleU& u) const override { return mix_.sample(wo, u); }
  float pdf(const glm::vec3& wi, const glm::vec3& wo) const override { return mix_.pdf(wi, wo); }

 private:
  GltfBsdf a_, b_;
  Mixture mix_;
};

// The renderer's glTF surface: one rough red dielectric, then that material with each extension
// layer alone at a typical setting (the transmission one refracting into a volume, as the
// integrator shades a KHR_materials_volume boundary from outside).
std::vector<std::pair<std::string, std::shared_ptr<const Bsdf>>> surface_cases() {
  ShadingParams base;
  base.base_color = Rgb(0.8f, 0.3f, 0.2f);
  base.metallic = 0.0f;
  base.roughness = 0.5f;
  std::vector<std::pair<std::string, ShadingParams>> cases;
  cases.push_back({"base", base});
  ShadingParams p = base;
  p.clearcoat = 1.0f, p.clearcoat_roughness = 0.1f;
  cases.push_back({"clearcoat", p});
  p = base;
  p.anisotropy = 0.6f, p.anisotropy_direction = glm::vec2(0.8f, 0.6f);
  cases.push_back({"anisotropy", p});
  p = base;
  p.sheen_color = Rgb(0.9f, 0.6f, 0.3f), p.sheen_roughness = 0.5f;
  cases.push_back({"sheen", p});
  p = base;
  p.iridescence = 1.0f, p.iridescence_ior = 1.3f, p.iridescence_thickness = 400.0f;
  cases.push_back({"iridescence", p});
  p = base;
  p.transmission = 1.0f, p.thin_walled = false, p.eta = 1.5f;
  cases.push_back({"transmission+volume", p});
  p = base;
  p.diffuse_transmission = 0.5f, p.diffuse_transmission_color = Rgb(0.6f, 0.9f, 0.3f);
  cases.push_back({"diffuse-transmission", p});
  std::vector<std::pair<std::string, std::shared_ptr<const Bsdf>>> out;
  for (const auto& [label, params] : cases) out.push_back({"surface/" + label, std::make_shared<SurfaceBsdf>(params)});
  return out;
}

struct Registrar {
  Registrar() {
    struct Case {
      std::string label, name;
      std::vector<std::string> params, impulses;
    };
    std::vector<Case> cases = {
        {"lambert", "lambert", {}, {}},
        {"phong", "phong", {}, {}},
        {"blinn-phong", "blinn-phong", {}, {}},
        {"lafortune/2lobes", "lafortune", {"lobe=-1,-1,1,20", "lobe=1,1,1,5,0.2,0.2,0.2"}, {}},
        {"microfacet/ggx", "microfacet", {}, {}},
        {"microfacet/beckmann", "microfacet", {"distribution=beckmann"}, {}},
        {"microfacet/ggx-conductor", "microfacet", {"fresnel=conductor"}, {}},
        {"cook-torrance", "cook-torrance", {}, {}},
        {"oren-nayar", "oren-nayar", {}, {}},
        {"sheen", "sheen", {"color=0.9,0.6,0.3", "roughness=0.5"}, {}},
        {"gltf", "gltf", {}, {}},
        {"mirror", "mirror", {}, {}},
        {"dielectric", "dielectric", {}, {}},
        {"conductor-mirror", "conductor-mirror", {}, {}},
        {"lambert+mirror:0.4", "lambert", {"albedo=0.2"}, {"mirror:0.4"}},
    };
    std::vector<std::pair<std::string, std::shared_ptr<const Bsdf>>> models;
    for (const Case& c : cases) models.push_back({c.label, make_model(c.name, c.params, c.impulses)});
    for (const auto& [label, bsdf] : models) benchmark::RegisterBenchmark(("eval-batch/" + label).c_str(), eval_batch_bench, bsdf);
    GltfParams g;
    g.roughness = 0.4f;
    models.push_back({"measured", std::make_shared<Measured>(std::make_shared<MerlTable>(MerlTable::tabulate(GltfBsdf(g))))});
    models.push_back({"mixture/2-gltf-lobes", std::make_shared<TwoGltfLobes>()});
    for (auto& c : surface_cases()) models.push_back(std::move(c));
    sheen_albedo(0.5f, 0.5f);  // the albedo table is built on first use, not inside the timing
    benchmark::RegisterBenchmark("sheen_albedo_scaling", sheen_scaling_bench);
    benchmark::RegisterBenchmark("iridescence_fresnel", thin_film_bench);
    for (const auto& [label, bsdf] : models) {
      benchmark::RegisterBenchmark(("eval/" + label).c_str(), eval_bench, bsdf);
      benchmark::RegisterBenchmark(("sample/" + label).c_str(), sample_bench, bsdf);
      benchmark::RegisterBenchmark(("pdf/" + label).c_str(), pdf_bench, bsdf);
    }
  }
} registrar;

}  // namespace
