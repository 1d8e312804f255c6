#include "render/renderer.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <mutex>
#include <thread>

#include <tbb/blocked_range2d.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "base/error.h"
#include "render/embree_device.h"

namespace svbrdf {

Film::Film(int w, int h)
    : width(w),
      height(h),
      radiance_sum(std::size_t(w) * h, glm::dvec3(0.0)),
      samples(std::size_t(w) * h, 0u),
      opaque(std::size_t(w) * h, 0u),
      albedo_sum(std::size_t(w) * h, glm::vec3(0.0f)),
      normal_sum(std::size_t(w) * h, glm::vec3(0.0f)),
      depth_sum(std::size_t(w) * h, 0.0f),
      level_sum(std::size_t(w) * h, 0.0f),
      frame{0, 0, w, h} {}

namespace {
template <typename F>
Image mean_image(const Film& f, int channels, F&& value) {
  Image im(f.width, f.height, channels);
  for (std::size_t p = 0; p < f.samples.size(); ++p) {
    if (f.samples[p] == 0) continue;
    const double inv = 1.0 / f.samples[p];
    for (int c = 0; c < channels; ++c) im.pixels[p * channels + c] = static_cast<float>(value(p, c) * inv);
  }
  return im;
}
}  // namespace

Image Film::radiance() const { return mean_image(*this, 3, [&](std::size_t p, int c) { return radiance_sum[p][c]; }); }
Image Film::alpha() const { return mean_image(*this, 1, [&](std::size_t p, int) { return double(opaque[p]); }); }
Image Film::albedo() const { return mean_image(*this, 3, [&](std::size_t p, int c) { return double(albedo_sum[p][c]); }); }
Image Film::normal() const { return mean_image(*this, 3, [&](std::size_t p, int c) { return double(normal_sum[p][c]); }); }
Image Film::depth() const { return mean_image(*this, 1, [&](std::size_t p, int) { return double(depth_sum[p]); }); }
Image Film::mip_level() const { return mean_image(*this, 1, [&](std::size_t p, int) { return double(level_sum[p]); }); }

std::uint64_t pixel_seed(std::uint64_t seed, int x, int y, int width) {
  const std::uint64_t pixel = std::uint64_t(y) * std::uint64_t(width) + std::uint64_t(x);
  return mix64(seed * 0x9E3779B97F4A7C15ULL + mix64(pixel + 1));
}

Rng pixel_rng(std::uint64_t seed, int x, int y, int width, std::uint32_t index) {
  return Rng(pixel_seed(seed, x, y, width), index);
}

std::vector<int> pass_starts(int spp) {
  std::vector<int> starts = {0};
  // In 64 bits: twice 2^30 passes INT_MAX.
  for (long long next = 1; starts.back() < spp; next = 2LL * starts.back()) starts.push_back(int(std::min<long long>(spp, next)));
  return starts;
}

float resolve_footprint_scale(float scale, int spp) {
  if (scale > 0.0f) return scale;
  return 1.0f / std::sqrt(static_cast<float>(std::max(spp, 1)));
}

Film render(const RenderWorld& world, const RenderOptions& opt, RenderStats* stats) {
  // The film holds the crop's pixels alone; a pixel keeps its place in the frame (fx, fy) for its
  // random numbers and its ray, so it is the pixel a render of the whole frame gives.
  const int frame_w = world.camera->width(), frame_h = world.camera->height();
  const PixelRect rect = opt.crop.empty() ? PixelRect{0, 0, frame_w, frame_h} : opt.crop;
  if (rect.x0 < 0 || rect.y0 < 0 || rect.x1 > frame_w || rect.y1 > frame_h)
    throw Error("render: the crop reaches past the " + std::to_string(frame_w) + "x" + std::to_string(frame_h) + " frame",
                Error::Kind::internal);
  const int w = rect.width(), h = rect.height();
  Film film(w, h);
  film.frame = {rect.x0, rect.y0, frame_w, frame_h};
  const int spp = std::max(opt.spp, 1);
  // The MIP data the filter reads, built now if PreparedScene has not already.
  if (world.mips) world.mips->prepare(opt.integrator.filter);
  IntegratorSettings integrator = opt.integrator;
  integrator.aovs = opt.aovs;
  integrator.footprint_scale = resolve_footprint_scale(integrator.footprint_scale, spp);
  // Passes over the whole frame of 1, 1, 2, 4, 8, ... samples per pixel: after pass k every pixel has
  // 2^k samples, so a render stopped between passes is the whole image at that count, and one stopped
  // within a pass has that count everywhere and up to twice it where the pass reached. The last passes
  // take most samples, so a pixel's samples still follow one another and find its texels in the cache
  // (16 passes of 4 samples streamed the texture through the cache 16 times: 7 % of the frame on
  // DamagedHelmet; bench/results/render.md). Each pixel's samples accumulate in index order whatever
  // the passes, so the image is the same bit for bit as one pass would give.
  const std::vector<int> passes = pass_starts(spp);
  constexpr int kTile = 16;
  const int tiles_x = (w + kTile - 1) / kTile, tiles_y = (h + kTile - 1) / kTile;

  std::atomic<std::uint64_t> rays{0}, samples_done{0};
  std::atomic<bool> stop{opt.cancel && opt.cancel->load()};  // a Ctrl-C while the MIP data was built
  bool timed_out = false;
  const auto start = std::chrono::steady_clock::now();
  auto elapsed = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(); };
  const std::uint64_t samples_total = std::uint64_t(w) * h * spp;

  // A watcher thread: the time limit and the cancel flag every 50 ms, progress reports every 0.2 s.
  // The workers read `stop` before every sample (a relaxed load, nothing beside a path's cost), so a
  // stop takes effect within 50 ms plus one sample per thread (after the first pass), whatever the
  // tile size and the number of samples per pixel: checked per tile, a 64×64 image at 10^7 spp ran
  // minutes past its limit.
  std::mutex m;
  std::condition_variable cv;
  bool finished = false;
  std::thread watcher([&] {
    std::unique_lock<std::mutex> lock(m);
    double last_progress = 0.0;
    while (!finished) {
      cv.wait_for(lock, std::chrono::milliseconds(50));
      if (finished) break;
      if (opt.cancel && opt.cancel->load()) stop = true;
      const double now = elapsed();
      if (opt.time_limit > 0.0 && now >= opt.time_limit) {
        timed_out = true;
        stop = true;
      }
      if (opt.progress && now - last_progress >= 0.2) {
        last_progress = now;
        opt.progress({samples_done.load(), samples_total, rays.load(), now});
      }
    }
  });

  tbb::task_arena arena(opt.threads > 0 ? opt.threads : tbb::task_arena::automatic);
  try {
    for (std::size_t pass = 0; pass + 1 < passes.size() && (pass == 0 || !stop); ++pass) {
      const int first = passes[pass], last = passes[pass + 1];
      // The first pass runs to its end whatever stops the render: an image with a sample in every
      // pixel is worth one sample per pixel's wait (a second Ctrl-C abandons the render: base/interrupt.h).
      const bool stoppable = pass > 0;
      arena.execute([&] {
        tbb::parallel_for(tbb::blocked_range2d<int>(0, tiles_y, 1, 0, tiles_x, 1), [&](const tbb::blocked_range2d<int>& r) {
          set_denormals_zero();  // DEPENDENCIES.md pitfall 6: in every thread that traces
          std::uint64_t tile_rays = 0, tile_samples = 0;
          for (int ty = r.rows().begin(); ty < r.rows().end(); ++ty)
            for (int tx = r.cols().begin(); tx < r.cols().end(); ++tx) {
              for (int y = ty * kTile; y < std::min(h, (ty + 1) * kTile); ++y)
                for (int x = tx * kTile; x < std::min(w, (tx + 1) * kTile); ++x) {
                  const std::size_t p = std::size_t(y) * w + x;
                  const int fx = rect.x0 + x, fy = rect.y0 + y;
                  const std::uint64_t seed = pixel_seed(opt.seed, fx, fy, frame_w);  // once per pixel, not per sample
                  for (int s = first; s < last; ++s) {
                    // Stopped: this pixel keeps the samples it has; the loops run out without tracing.
                    if (stoppable && stop.load(std::memory_order_relaxed)) break;
                    Rng rng(seed, std::uint32_t(s));  // pixel_rng(opt.seed, fx, fy, frame_w, s)
                    const float jx = rng.next_float(), jy = rng.next_float();
                    const PathSample ps = trace_path(world, integrator, float(fx) + jx, float(fy) + jy, rng);
                    tile_rays += ps.rays;
                    // A non-finite sample would poison the pixel; it counts as black (never seen in tests).
                    const Rgb L = std::isfinite(ps.radiance.x + ps.radiance.y + ps.radiance.z) ? ps.radiance : Rgb(0.0f);
                    film.radiance_sum[p] += glm::dvec3(L);
                    if (opt.aovs) {
                      film.albedo_sum[p] += ps.albedo;
                      film.normal_sum[p] += ps.normal;
                      film.depth_sum[p] += ps.depth;
                      film.level_sum[p] += ps.mip_level;
                    }
                    ++film.samples[p];
                    film.opaque[p] += ps.opaque;
                    ++tile_samples;
                  }
                }
            }
          rays += tile_rays;
          samples_done += tile_samples;
        });
      });
    }
  } catch (...) {
    {
      std::lock_guard<std::mutex> lock(m);
      finished = true;
    }
    cv.notify_all();
    watcher.join();
    throw;
  }
  {
    std::lock_guard<std::mutex> lock(m);
    finished = true;
  }
  cv.notify_all();
  watcher.join();
  if (opt.progress) opt.progress({samples_done.load(), samples_total, rays.load(), elapsed()});
  if (stats) {
    stats->seconds = elapsed();
    stats->rays = rays.load();
    stats->samples = samples_done.load();
    stats->timed_out = timed_out;
    stats->interrupted = !timed_out && stop.load();
    const auto [fewest, most] = std::minmax_element(film.samples.begin(), film.samples.end());
    stats->pixel_samples_min = film.samples.empty() ? 0 : *fewest;
    stats->pixel_samples_max = film.samples.empty() ? 0 : *most;
  }
  return film;
}

}  // namespace svbrdf
