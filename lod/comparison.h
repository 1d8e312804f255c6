#pragma once
// The distance-LOD comparison: for every case of the LOD manifest (scenes/lod_scenes.h),
// view, light and distance, render the texture filters under test and the ground truth, and measure
// them (scenes/lod_metrics.h).
//
// Every image is rendered by the render module in this process (svbrdf::render), at the manifest's
// image size, with the same pixel filter (the renderer's box: uniform jitter in the pixel) and the
// same number of samples per pixel:
//   - the ground truth: `--filter level0` (the nearest texel at the exact uv, no MIP: with many
//     samples per pixel, the supersampled exact answer) with seed `seed`;
//   - the ground truth again with `second_seed`: the noise floor is the metrics between the two;
//   - each filter (`param`, the baselines, `brdf`) with `filter_seed`, a third seed, so that no
//     filter render shares random numbers (sample positions in the pixel) with the ground truth it
//     is measured against.
// For the tile roof the ground truth renders the real geometry (the case's reference file) and the
// filters render the flat proxy.
//
// Filters the renderer does not offer are reported as unavailable and skipped, never replaced: a
// filter is available when svbrdf-render knows its name (parse_filter) *and* a probe render of the
// first case's farthest camera under it differs from the level0 render with the same seed (a
// renderer that accepted the name but ignored it would render bit-identical images).
#include <cmath>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "lod/metrics.h"
#include "scenes/lod_scenes.h"
#include "textures/color.h"
#include "textures/image.h"

namespace svbrdf {

struct LodOptions {
  int spp = 256;  // every render: ground truths and filters
  std::uint64_t seed = 1, second_seed = 2, filter_seed = 3;
  // What to compare against the ground truth, in this order (the report's columns).
  std::vector<std::string> filters{"param", "toksvig", "vmf", "brdf"};
  double min_distance = 0.0;        // skip cameras nearer than this multiple of d₁
  double max_distance = INFINITY;   // and farther than this one
  std::vector<double> distances;    // empty: every distance in that range; else only these multiples
  std::vector<std::string> cases;   // empty: all
  std::vector<std::string> lights;  // empty: all
  std::vector<std::string> views;   // empty: all
  int threads = 0;                  // 0: all cores
  // The filters' footprint scale (IntegratorSettings::footprint_scale): 0 is the renderer's default,
  // 1/√spp — each of the pixel's jittered samples filters its share of the pixel; 1 makes every
  // sample filter the whole pixel footprint.
  float footprint_scale = 0.0f;
  bool keep_images = true;          // keep the images (the report needs them; the tests do not)
  // A part of the comparison, for a farm (lod/parts.h): of the selected shots, numbered k = 0, 1, ...
  // in the comparison's order (case, view, light, distance, as the manifest lists them), render only
  // those with k mod parts == part. A shot's renders depend on the shot alone (its seeds are the
  // options' and its camera its own), so the parts' shots are the single run's, bit for bit.
  int part = 0, parts = 1;
  std::function<void(const std::string&)> progress;  // one line per shot
};

// One (case, view, light, distance): the ground truth's noise floor and each filter's metrics.
struct LodShot {
  int index = 0;  // k: the shot's place among every selected shot of the comparison (all parts)
  std::string case_name, kind, view, light, camera;
  double multiple = 1.0;
  LodMetrics floor;         // second ground truth against the first
  double flux_sigma = 0.0;  // relative σ of one ground truth's flux (lod_metrics.h flux_noise)
  struct FilterResult {
    std::string filter;
    LodMetrics metrics;
    Image image;  // radiance (kept when keep_images)
  };
  std::vector<FilterResult> filters;
  Image truth, truth2;             // kept when keep_images
  std::vector<std::uint8_t> mask;  // the object mask (of the first ground truth)

  const FilterResult* find(const std::string& filter) const;
};

struct LodResults {
  LodOptions options;
  int image_size = 0;
  std::vector<std::string> filters;      // the available ones, in options order
  std::vector<std::string> unavailable;  // asked for but not offered by the renderer
  std::vector<LodShot> shots;   // this part's (all of them for one part), by index
  int total_shots = 0;          // the selected shots of the whole comparison, over all parts
  double seconds = 0.0;
};

// Throws svbrdf::Error for a manifest whose files are missing or malformed, or an unknown name in
// options.cases / lights / views.
LodResults run_lod_comparison(const LodManifest& manifest, const LodOptions& options,
                              const ColorConfig& color = ColorConfig::builtin());

}  // namespace svbrdf
