#pragma once
// Rendering an image: passes over the whole frame of 1, 1, 2, 4, ... samples per pixel (pass_starts),
// each in 16×16 tiles spread over oneTBB, every sample seeded by (seed, pixel, sample index) so the
// image is bit-identical for any thread count and any pass split. An interruption (Ctrl-C,
// --time-limit) stops within a fraction of a second, before each thread's next sample, once the first
// pass is done: every pixel then holds the mean of the samples it got, at least the count of the last
// finished pass and at most twice it.
#include <atomic>
#include <cstdint>
#include <functional>
#include <vector>

#include "render/crop.h"
#include "render/integrator.h"
#include "textures/image.h"

namespace svbrdf {

// Accumulated samples: per pixel the sum of radiance, the number of samples and of opaque ones
// (PathSample::opaque), plus the first-hit AOVs (sums too).
struct Film {
  int width = 0, height = 0;
  std::vector<glm::dvec3> radiance_sum;
  std::vector<std::uint32_t> samples, opaque;
  std::vector<glm::vec3> albedo_sum, normal_sum;
  std::vector<float> depth_sum, level_sum;
  // Where these width × height pixels lie in the camera's frame: all of it, or RenderOptions::crop.
  FrameWindow frame;

  // What one pixel costs while rendering: the sums above, plus the images written at the end (the
  // EXR's 12 channels with its AOV layers, the display image's 4).
  static constexpr std::uint64_t kBytesPerPixel = sizeof(glm::dvec3) + 2 * sizeof(std::uint32_t) + 2 * sizeof(glm::vec3) +
                                                  2 * sizeof(float) + (12 + 4) * sizeof(float);

  Film(int w, int h);
  // Means per pixel (zero where no sample landed): RGB radiance; alpha, the share of opaque samples
  // (the radiance is premultiplied by it: a sample that is not opaque brings back zero); RGB albedo,
  // XYZ normal, depth, MIP level.
  Image radiance() const;
  Image alpha() const;
  Image albedo() const;
  Image normal() const;
  Image depth() const;
  Image mip_level() const;
};

struct ProgressInfo {
  std::uint64_t samples_done = 0, samples_total = 0;
  std::uint64_t rays = 0;
  double seconds = 0.0;
};

struct RenderOptions {
  int spp = 64;
  int threads = 0;  // 0: all cores
  std::uint64_t seed = 0;
  IntegratorSettings integrator;
  bool aovs = true;                         // accumulate albedo, normal, depth and MIP level
  PixelRect crop;                           // the part of the frame to render; empty: all of it
  double time_limit = 0.0;                  // seconds; 0 = none
  const std::atomic<bool>* cancel = nullptr;  // set by a signal handler (Ctrl-C, SIGTERM)
  std::function<void(const ProgressInfo&)> progress;  // called about every 0.2 s from one thread
};

struct RenderStats {
  double seconds = 0.0;
  std::uint64_t rays = 0;
  std::uint64_t samples = 0;
  bool interrupted = false;  // cancelled (Ctrl-C)
  bool timed_out = false;    // stopped by the time limit
  // The fewest and the most samples a pixel got: spp both when the render ran to its end.
  std::uint32_t pixel_samples_min = 0, pixel_samples_max = 0;
};

// Prepares world.mips for options.integrator.filter first (material_mips.h; the time that takes is
// not in stats), and resolves a footprint_scale of 0 to 1/√spp (resolve_footprint_scale).
Film render(const RenderWorld& world, const RenderOptions& options, RenderStats* stats = nullptr);

// Where the passes of a render of `spp` samples per pixel begin, and spp where the last ends:
// {0, 1, 2, 4, ..., spp}. Pass k takes samples [starts[k], starts[k+1]) of every pixel.
std::vector<int> pass_starts(int spp);

// The footprint scale a render uses: `scale` where given (> 0), else 1/√spp — each of the pixel's spp
// jittered samples filters its share of the pixel, so the MIP lookups read log2(1/scale) levels finer
// than the whole pixel's footprint. pbrt-v4 stops at 1/8 (max(1/8, 1/√spp)); we do not, because with
// that floor every MIP filter converges, as samples grow, to the pixel's image blurred by an eighth of
// a pixel, not to the pixel's image: the LOD comparison measured it (a far mirror view of the metal tray
// 1.59× its noise floor at 4096 spp and 3.25× at 6000, 1.13× with 1/√spp; docs/design-notes.md).
// With 1/√spp the filter's blur shrinks with the noise, so its bias shrinks at least as fast.
float resolve_footprint_scale(float scale, int spp);

// The random-number generator of sample `index` of pixel (x, y): independent of everything else. It
// is Rng(pixel_seed(seed, x, y, width), index); the renderer mixes a pixel's seed once for all its samples.
std::uint64_t pixel_seed(std::uint64_t seed, int x, int y, int width);
Rng pixel_rng(std::uint64_t seed, int x, int y, int width, std::uint32_t index);

}  // namespace svbrdf
