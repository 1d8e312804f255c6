// svbrdf-lod-report: the distance-LOD comparison and its HTML report. Renders every LOD
// scene of the manifest (the build's <build>/scenes/lod/manifest.json by default) under each
// texture filter and the ground truth, and writes DIR/index.html (default out/lod-report).
// --full is the report's size (4096 samples per pixel); the default size is what the tests run.
// On a farm: --part I/N --part-out DIR renders part I of N of the shots into DIR (lod/parts.h), and
// --assemble DIR writes the report of all of them, the single run's; --slurm submits both (docs/farm.md).
#include <CLI/CLI.hpp>

#include <climits>
#include <cstdio>
#include <filesystem>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "apps/baked_scenes.h"
#include "apps/lod_slurm.h"
#include "apps/run_program.h"
#include "base/cli_checks.h"
#include "base/error.h"
#include "base/interrupt.h"
#include "base/output_location.h"
#include "lod/comparison.h"
#include "lod/parts.h"
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

// "I/N" of --part: 0 <= I < N.
std::pair<int, int> parse_part(const std::string& text) {
  int i = -1, n = 0;
  char extra = 0;
  if (std::sscanf(text.c_str(), "%d/%d%c", &i, &n, &extra) != 2 || n < 1 || i < 0 || i >= n)
    throw svbrdf::input_error("--part " + text, "must be I/N with 0 <= I < N, e.g. 0/8");
  return {i, n};
}

// The command line as the report shows it, without the options in `drop` (each with its value).
std::string command_text(int argc, char** argv, const std::vector<std::string>& drop) {
  std::string out = "svbrdf-lod-report";
  for (const std::string& a : svbrdf::without_options(std::vector<std::string>(argv + 1, argv + argc), drop)) out += " " + a;
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  // A Ctrl-C or SIGTERM: one line and exit 130 / 143, no temporary left (base/interrupt.h). The
  // report is written at the end, so there is nothing to keep from an interrupted comparison.
  svbrdf::install_interrupt_handlers("svbrdf-lod-report");
  CLI::App app{"svbrdf-lod-report: render the distance-LOD scenes under each texture filter and the ground truth, "
               "and write an HTML report"};
  std::string manifest, out = "out/lod-report", ocio, part, part_out, assemble;
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
  app.add_option("--part", part,
                 "render only part I of N (I from 0, as Slurm numbers array tasks): of the selected shots, numbered "
                 "k = 0, 1, ... by case, view, light and distance as the manifest lists them, those with k mod N = I; "
                 "needs --part-out");
  app.add_option("--part-out", part_out,
                 "with --part: the folder the parts share; the part writes lod-part-I-of-N.json and its images "
                 "(EXR) there instead of a report (with --slurm: the parts' folder, default OUT.parts)");
  app.add_option("--assemble", assemble,
                 "write the report (-o) of the parts in this folder, as the single run writes it; refuses a part "
                 "missing, corrupt, copied or of another comparison")
      ->excludes("--part");
  svbrdf::LodSlurmOptions slurm;
  slurm.add_to(app);
  return svbrdf::run_program("svbrdf-lod-report", app, argc, argv, [&] {
    const svbrdf::ColorConfig color =
        svbrdf::ColorConfig::resolve(ocio.empty() ? std::nullopt : std::optional<fs::path>(ocio));
    if (!assemble.empty()) {
      if (!slurm.mode.empty()) throw svbrdf::input_error("--slurm", "submits the assembly itself; leave out --assemble");
      svbrdf::LodPartRun run;
      const svbrdf::LodResults results = svbrdf::read_lod_parts(assemble, run);
      const svbrdf::LodManifest m = svbrdf::read_lod_manifest(run.manifest);
      if (m.image_size != results.image_size)
        throw svbrdf::input_error(run.manifest.string(), "its image size is not the parts' (changed since they ran?)");
      svbrdf::check_output_folder(fs::path(out) / "img");
      const fs::path index = svbrdf::write_lod_report(results, m, out, {.size_name = run.size_name, .command = run.command}, color);
      if (!quiet) std::fprintf(stderr, "svbrdf-lod-report: wrote %s from %d parts\n", index.c_str(), results.options.parts);
      return 0;
    }
    if (part.empty() != part_out.empty() && slurm.mode.empty())
      throw svbrdf::input_error(part.empty() ? "--part-out" : "--part", "--part and --part-out go together");
    const fs::path manifest_path = manifest.empty() ? default_manifest(argv[0]) : fs::path(manifest);
    const svbrdf::LodManifest m = svbrdf::read_lod_manifest(manifest_path);
    if (!slurm.mode.empty()) {
      if (!part.empty()) throw svbrdf::input_error("--slurm", "numbers the parts itself (--slurm-parts); leave out --part");
      svbrdf::run_lod_slurm(slurm, out, part_out, ocio, argc, argv);
      return 0;
    }
    svbrdf::LodOptions o;
    o.spp = spp > 0 ? spp : full ? 4096 : 256;
    o.threads = svbrdf::cli::capped_threads(threads, "svbrdf-lod-report");
    o.min_distance = min_distance;
    o.max_distance = max_distance;
    o.footprint_scale = footprint_scale;
    o.cases = cases, o.lights = lights, o.views = views;
    if (!filters.empty()) o.filters = filters;
    if (!part.empty()) std::tie(o.part, o.parts) = parse_part(part);
    if (!quiet) o.progress = [](const std::string& s) { std::fprintf(stderr, "svbrdf-lod-report: %s\n", s.c_str()); };
    // Before the comparison (minutes to hours): the report's (or the part's) folder must take its files.
    svbrdf::check_output_folder(part.empty() ? fs::path(out) / "img" : fs::path(part_out));
    const svbrdf::LodResults results = svbrdf::run_lod_comparison(m, o, color);
    svbrdf::LodReportInfo info;
    info.size_name = spp > 0 ? std::to_string(spp) + " spp" : full ? "full" : "default";
    info.command = command_text(argc, argv, {});
    if (!part.empty()) {
      std::error_code ec;
      fs::create_directories(part_out, ec);
      if (ec) throw svbrdf::environment_error(part_out, "cannot create the parts' folder: " + ec.message());
      const svbrdf::LodPartRun run{fs::absolute(manifest_path).lexically_normal(), info.size_name,
                                   command_text(argc, argv, {"--part", "--part-out"})};
      svbrdf::write_lod_part(results, run, part_out);
      if (!quiet)
        std::fprintf(stderr, "svbrdf-lod-report: wrote part %d of %d (%zu of %d shots) in %s (%.0f s)\n", o.part, o.parts,
                     results.shots.size(), results.total_shots, part_out.c_str(), results.seconds);
      return 0;
    }
    const fs::path index = svbrdf::write_lod_report(results, m, out, info, color);
    if (!quiet) std::fprintf(stderr, "svbrdf-lod-report: wrote %s (%.0f s)\n", index.c_str(), results.seconds);
    return 0;
  });
}
