// Texture throughput: images read per second (files and memory, the formats glTF and the MIP
// files use), texel lookups, the texture-set decode, and megatexels per second for 4096² bakes.
// Results and commands: bench/results/textures.md.
#include <benchmark/benchmark.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <unistd.h>

#include "textures/material_family.h"
#include "textures/material_loader.h"
#include "textures/sampler.h"
#include "scenes/texture_set.h"

namespace svbrdf {
namespace {

namespace fs = std::filesystem;

// A scratch directory removed when the program ends.
struct Scratch {
  fs::path dir = fs::temp_directory_path() / ("svbrdf_bench_textures_" + std::to_string(::getpid()));
  Scratch() { fs::create_directories(dir); }
  ~Scratch() {
    std::error_code ec;
    fs::remove_all(dir, ec);
  }
};
const fs::path& scratch() {
  static const Scratch s;
  return s.dir;
}

// A 1024² painted-wall texture set on disk, baked once: realistic content for the readers.
const TextureSetFiles& files_1024() {
  static const TextureSetFiles files = bake_material(MaterialRecipe{"painted-wall", "", 1024, 1, 0.0}, scratch() / "wall");
  return files;
}

void read_file(benchmark::State& state, const fs::path& path) {
  std::size_t texels = 0;
  for (auto _ : state) {
    const Image img = read_image(path);
    texels += std::size_t(img.width) * img.height;
    benchmark::DoNotOptimize(img.pixels.data());
  }
  state.counters["images/s"] = benchmark::Counter(double(state.iterations()), benchmark::Counter::kIsRate);
  state.counters["Mtexels/s"] = benchmark::Counter(double(texels) * 1e-6, benchmark::Counter::kIsRate);
}

void BM_ReadPng8Rgb1024(benchmark::State& state) {
  // The painted wall's base color is 16-bit; make an 8-bit one from it once.
  static const fs::path p = [] {
    const fs::path out = scratch() / "base8.png";
    write_image(out, read_image(files_1024().base_color), PixelFormat::uint8);
    return out;
  }();
  read_file(state, p);
}
void BM_ReadPng16Rgb1024(benchmark::State& state) { read_file(state, files_1024().normal); }
void BM_ReadExrHalfRgb1024(benchmark::State& state) {
  static const fs::path p = [] {
    const fs::path out = scratch() / "normal_half.exr";
    write_image(out, read_image(files_1024().normal), PixelFormat::half);
    return out;
  }();
  read_file(state, p);
}
void BM_ReadPngFromMemory1024(benchmark::State& state) {
  std::ifstream f(files_1024().normal, std::ios::binary);
  std::vector<char> chars((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
  const std::span<const std::byte> bytes(reinterpret_cast<const std::byte*>(chars.data()), chars.size());
  for (auto _ : state) benchmark::DoNotOptimize(read_image_from_memory(bytes, "image/png", "bench").pixels.data());
  state.counters["images/s"] = benchmark::Counter(double(state.iterations()), benchmark::Counter::kIsRate);
}

// Three PNGs → MaterialTexels (sRGB decode through OCIO, normal decode).
void BM_LoadMaterialTexels1024(benchmark::State& state) {
  MaterialFiles in;
  in.base_color = files_1024().base_color;
  in.metallic_roughness = files_1024().metallic_roughness;
  in.normal = files_1024().normal;
  for (auto _ : state) benchmark::DoNotOptimize(load_material_texels(in).base_color.data());
  state.counters["Mtexels/s"] = benchmark::Counter(double(state.iterations()) * 1024 * 1024 * 1e-6, benchmark::Counter::kIsRate);
}

void BM_SampleBilinear(benchmark::State& state) {
  static const Image img = read_image(files_1024().normal);
  const Sampler s{FilterMode::bilinear, WrapMode::repeat, WrapMode::mirrored_repeat};
  const TextureTransform t = TextureTransform::make({0.1f, 0.2f}, 0.3f, {2.0f, 2.0f});
  float u = 0.0f;
  for (auto _ : state) {
    u += 0.000123f;
    benchmark::DoNotOptimize(sample(img, s, t.apply({u, 0.37f * u})));
  }
  state.SetItemsProcessed(state.iterations());
}

const char* const kPresets[] = {"sandstone", "painted-wall", "printed-paper", "metal-tray", "granite"};

// generate_material at 4096² (pattern, normals, encoding, decode): megatexels per second.
void BM_Generate4096(benchmark::State& state) {
  const char* preset = kPresets[state.range(0)];
  state.SetLabel(preset);
  for (auto _ : state) benchmark::DoNotOptimize(generate_material(MaterialRecipe{preset, "", 4096, 1, 0.0}).texels.size());
  state.counters["Mtexels/s"] = benchmark::Counter(double(state.iterations()) * 4096.0 * 4096.0 * 1e-6, benchmark::Counter::kIsRate);
}

// The whole `svbrdf-bake material PRESET --size 4096`: generate + three PNGs + glTF.
void BM_Bake4096(benchmark::State& state) {
  const char* preset = kPresets[state.range(0)];
  state.SetLabel(preset);
  for (auto _ : state) bake_material(MaterialRecipe{preset, "", 4096, 1, 0.0}, scratch() / "bake");
  state.counters["Mtexels/s"] = benchmark::Counter(double(state.iterations()) * 4096.0 * 4096.0 * 1e-6, benchmark::Counter::kIsRate);
}

// Rates are per wall-clock second (UseRealTime): the decode, the bakes and the OCIO passes run
// on all cores, and a rate by the main thread's CPU time would overstate them.
BENCHMARK(BM_ReadPng8Rgb1024)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_ReadPng16Rgb1024)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_ReadExrHalfRgb1024)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_ReadPngFromMemory1024)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_LoadMaterialTexels1024)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_SampleBilinear);
BENCHMARK(BM_Generate4096)->DenseRange(0, 4)->Iterations(1)->Unit(benchmark::kSecond)->UseRealTime();
BENCHMARK(BM_Bake4096)->DenseRange(0, 4)->Iterations(1)->Unit(benchmark::kSecond)->UseRealTime();

}  // namespace
}  // namespace svbrdf
