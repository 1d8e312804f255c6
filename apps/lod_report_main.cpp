// svbrdf-lod-report: the distance-LOD comparison and its HTML report. Renders every LOD
// scene of the manifest (the build's <build>/scenes/lod/manifest.json by default) under each
// texture filter and the ground truth, and writes DIR/index.html (default out/lod-report).
// --full is the report's size (4096 samples per pixel); the default size is what the tests run.
#include <CLI/CLI.hpp>

#include <climits>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "apps/baked_scenes.h"
#include "apps/run_program.h"
#include "base/cli_checks.h"
#include "base/interrupt.h"
#include "base/output_location.h"
#include "lod/comparison.h"
#include "lod/report.h"
#include "scenes/lod_scenes.h"
#include "textures/color.h"

namespace fs = std::filesystem;

namespace {

// The LOD manifest the build bakes: <build>/scenes/lod/manifest.json, the program being at <build>/
// (or its installed copy, apps/baked_scenes.h); the build tree's path where neither exists, for the
// line that says it is missing.
fs::path default_manifest(const char* argv0) {
  const fs::path relative = fs::path("lod") / "manifest.json";
  return svbrdf::find_baked_scene(argv0, relative).value_or(svbrdf::baked_scene_folders(argv0).front() / relative);
}

}  // namespace

int main(int argc, char** argv) {
  // A Ctrl-C or SIGTERM: one line and exit 130 / 143, no temporary left (base/interrupt.h). The
  // report is written at the end, so there is nothing to keep from an interrupted comparison.
  svbrdf::install_interrupt_handlers("svbrdf-lod-report");
  CLI::App app{"svbrdf-lod-report: render the distance-LOD scenes under each texture filter and the ground truth, "
               "and write an HTML report"};
  std::string manifest, out = "out/lod-report", ocio;
  bool full = false, quiet = false;
  int spp = 0, threads = 0;
  double min_distance = 0.0, max_distance = INFINITY;
  float footprint_scale = 0.0f;
  std::vector<std::string> cases, lights, views, filters;
  app.add_option("--manifest", manifest, "LOD manifest (default: the one the build baked beside this program)");
  app.add_option("-o,--out", out, "report directory (index.html and img/)");
  app.add_flag("--full", full, "the report's size: 4096 samples per pixel (default: 256, the tests' size)");
  app.add_option("--spp", spp, "samples per pixel of every render (overrides the size)")->check(svbrdf::cli::whole_in(1, INT_MAX));
  app.add_option("--threads", threads, "worker threads (0: all cores; more than the machine runs at once are capped)")
      ->check(svbrdf::cli::whole_in(0, INT_MAX));
  app.add_option("--min-distance", min_distance, "skip cameras nearer than this multiple of d1")
      ->check(svbrdf::cli::non_negative);
  app.add_option("--max-distance", max_distance, "skip cameras farther than this multiple of d1")
      ->check(svbrdf::cli::positive);
  app.add_option("--footprint-scale", footprint_scale,
                 "the filters' footprint scale, in [0, 64]: at k x d1 they read MIP level log2(k x scale) (default 0: "
                 "the renderer's 1/sqrt(spp); 1: each sample filters the whole pixel)")
      ->check(svbrdf::cli::number_in(0.0, 64.0));
  app.add_option("--case", cases, "only these cases (repeatable)");
  app.add_option("--light", lights, "only these lights (repeatable)");
  app.add_option("--view", views, "only these views: head-on, mirror (repeatable)");
  app.add_option("--filter", filters, "filters to compare (default: param toksvig vmf brdf)");
  app.add_option("--ocio-config", ocio, "OpenColorIO config for the report's PNGs (default: $OCIO, else the built-in one)");
  app.add_flag("-q,--quiet", quiet, "no progress lines");
  return svbrdf::run_program("svbrdf-lod-report", app, argc, argv, [&] {
    const svbrdf::ColorConfig color =
        svbrdf::ColorConfig::resolve(ocio.empty() ? std::nullopt : std::optional<fs::path>(ocio));
    const fs::path manifest_path = manifest.empty() ? default_manifest(argv[0]) : fs::path(manifest);
    const svbrdf::LodManifest m = svbrdf::read_lod_manifest(manifest_path);
    svbrdf::LodOptions o;
    o.spp = spp > 0 ? spp : full ? 4096 : 256;
    o.threads = svbrdf::cli::capped_threads(threads, "svbrdf-lod-report");
    o.min_distance = min_distance;
    o.max_distance = max_distance;
    o.footprint_scale = footprint_scale;
    o.cases = cases, o.lights = lights, o.views = views;
    if (!filters.empty()) o.filters = filters;
    if (!quiet) o.progress = [](const std::string& s) { std::fprintf(stderr, "svbrdf-lod-report: %s\n", s.c_str()); };
    // Before the comparison (minutes to hours): the report's folder must take its files.
    svbrdf::check_output_folder(fs::path(out) / "img");
    const svbrdf::LodResults results = svbrdf::run_lod_comparison(m, o, color);
    svbrdf::LodReportInfo info;
    info.size_name = spp > 0 ? std::to_string(spp) + " spp" : full ? "full" : "default";
    for (int i = 0; i < argc; ++i) info.command += (i ? " " : "") + std::string(i ? argv[i] : "svbrdf-lod-report");
    const fs::path index = svbrdf::write_lod_report(results, m, out, info, color);
    if (!quiet) std::fprintf(stderr, "svbrdf-lod-report: wrote %s (%.0f s)\n", index.c_str(), results.seconds);
    return 0;
  });
}
