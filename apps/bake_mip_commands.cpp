// `svbrdf-bake mip | eval | compare` (../shared/spec/brdf-mip.md, "svbrdf-bake surface"):
//   mip (--base-color IMG | --base-color-factor r,g,b) [--normal IMG [--normal-scale s]]
//       [--metallic-roughness IMG] [--metallic-factor m] [--roughness-factor r] [--lobes K] --out FILE
//   mip SCENE.gltf --material NAME|INDEX [--lobes K] --out FILE
//   mip SCENE.gltf [--mip-cache DIR] [--mip-cache-size MB]   (every material into the MIP cache)
//   eval FILE --level L --texel I J --mode exact|param|toksvig|vmf|brdf   (pairs on stdin)
//   compare FILE [--levels a..b] [--json] [--subset N]
#include <CLI/CLI.hpp>

#include <chrono>
#include <climits>
#include <cstdint>
#include <cstdio>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "apps/direction_text.h"
#include "apps/mip_cache_options.h"
#include "base/cli_checks.h"
#include "base/error.h"
#include "base/output_location.h"
#include "base/resource_limits.h"
#include "apps/bake_commands.h"
#include "apps/compare_report.h"
#include "base/setup_progress.h"
#include "gltf/scene_reader.h"
#include "mip/gltf_material.h"
#include "mip/mip_file.h"
#include "render/material_mips.h"
#include "textures/color.h"
#include "textures/material_loader.h"

namespace svbrdf {

namespace {

struct MipOptions {
  std::string scene, material, base_color, normal, metallic_roughness, out, ocio_config;
  std::vector<float> base_color_factor;
  float normal_scale = 1.0f, metallic_factor = 1.0f, roughness_factor = 1.0f;
  int lobes = kDefaultLobes;
  float tolerance = ReductionOptions{}.tolerance;
  bool normal_scale_set = false;
  int stats = 0;
  std::uint64_t max_texels = resource_limits().max_texels;
  MipCacheOptions cache;
};

// The largest |--normal-scale|: at 1000 a normal map's 8-bit step of 1/255 already tilts the normal
// by 76°, so any larger scale gives the same binary field of grazing normals; anything past it is a
// typo.
constexpr double kMaxNormalScale = 1000.0;

// --max-texels for the commands that read images or MIP files (base/resource_limits.h).
void add_max_texels_option(CLI::App* cmd, std::uint64_t& max_texels) {
  cmd->add_option("--max-texels", max_texels,
                  "the most texels one image or MIP level may have (default 2^26 = 8192x8192; at most 2^40)")
      ->check(cli::whole_in(1, cli::kMaxTexelsOption));
}

// `mip SCENE.gltf` without --material: every material's brdf build into the MIP cache, as
// svbrdf-render builds it (its scene reader, textures and materials' set-up, so the same keys), for
// renders that then build nothing.
void fill_mip_cache(const MipOptions& o) {
  if (!o.out.empty()) throw input_error("--out", "a whole glTF file goes into the MIP cache; --out goes with --material or images");
  if (!o.base_color.empty() || !o.normal.empty() || !o.metallic_roughness.empty() || !o.base_color_factor.empty())
    throw input_error(o.scene, "give either a glTF file or image options, not both");
  if (o.lobes != kDefaultLobes || o.tolerance != ReductionOptions{}.tolerance || o.stats != 0)
    throw input_error(o.scene, "--lobes, --tolerance and --stats go with --material: the MIP cache holds the builds "
                               "svbrdf-render makes, with the default options");
  if (o.cache.folder == "off") throw input_error("--mip-cache off", "a whole glTF file goes into the MIP cache; name one");
  const std::unique_ptr<MipCache> cache = o.cache.open("svbrdf-bake");
  if (!cache) throw environment_error("--mip-cache", "no MIP cache folder to fill");
  const ColorConfig color =
      ColorConfig::resolve(o.ocio_config.empty() ? std::nullopt : std::optional<std::filesystem::path>(o.ocio_config));
  SetupProgress progress("svbrdf-bake", false);
  progress.begin("reading " + std::filesystem::path(o.scene).filename().string() + " and decoding its images");
  const Scene scene = load_gltf(o.scene);
  progress.end();
  const TextureSet textures(scene, color);
  SceneMips mips(scene, textures);
  mips.use_cache(cache.get(), color.identity());
  mips.prepare(TextureFilter::brdf, &progress);
  progress.end();
  for (const std::string& w : mips.warnings(TextureFilter::brdf))
    std::fprintf(stderr, "svbrdf-bake: warning: %s\n", message_line(w).c_str());
  print_mip_cache_warnings(cache.get(), "svbrdf-bake");
  if (cache->store_failed()) throw environment_error(cache->folder().string(), "the MIP cache could not be filled");
  const SceneMips::CacheCounts c = mips.cache_counts();
  std::printf("%s: %d MIP maps in the MIP cache %s (%d were there, %d built)\n", o.scene.c_str(), c.read + c.built,
              cache->folder().c_str(), c.read, c.built);
}

void run_mip(const MipOptions& o) {
  resource_limits().max_texels = o.max_texels;  // before any image is read
  if (!o.scene.empty() && o.material.empty()) return fill_mip_cache(o);
  if (o.out.empty()) throw input_error("--out", "the MIP file to write is required (or a glTF file alone, to fill the MIP cache)");
  if (o.lobes < 1 || o.lobes > kMaxLobes)
    throw input_error("--lobes", std::to_string(o.lobes) + " is out of range (1.." + std::to_string(kMaxLobes) + ")");
  if (!(o.tolerance >= 0 && o.tolerance < 1)) throw input_error("--tolerance", "must be in [0, 1)");
  if (std::filesystem::path(o.out).extension() != ".exr") throw input_error("--out", "'" + o.out + "' must end in .exr (an OpenEXR file)");
  check_output_location(o.out);  // before the build: its seconds must not end in "cannot write"
  const ColorConfig color =
      ColorConfig::resolve(o.ocio_config.empty() ? std::nullopt : std::optional<std::filesystem::path>(o.ocio_config));
  // Each stage's wall time goes into the summary line: bench/mip/cold_build.sh reads it.
  const auto seconds_since = [](std::chrono::steady_clock::time_point t) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
  };
  const auto decode_start = std::chrono::steady_clock::now();
  MaterialTexels texels;
  if (!o.scene.empty()) {
    if (!o.base_color.empty() || !o.normal.empty() || !o.metallic_roughness.empty() || !o.base_color_factor.empty())
      throw input_error(o.scene, "give either a glTF file with --material or image options, not both");
    texels = load_gltf_material_texels(o.scene, o.material, color);
  } else {
    if (!o.material.empty()) throw input_error("--material", "only goes with a glTF file");
    if (o.base_color.empty() && o.base_color_factor.empty())
      throw input_error("", "give --base-color IMG or --base-color-factor r,g,b (or a glTF file with --material)");
    if (o.normal_scale_set && o.normal.empty()) throw input_error("--normal-scale", "only goes with --normal IMG");
    MaterialFiles f;
    if (!o.base_color.empty()) f.base_color = o.base_color;
    if (!o.base_color_factor.empty()) f.base_color_factor = glm::vec4(o.base_color_factor[0], o.base_color_factor[1], o.base_color_factor[2], 1.0f);
    if (!o.metallic_roughness.empty()) f.metallic_roughness = o.metallic_roughness;
    f.metallic_factor = o.metallic_factor;
    f.roughness_factor = o.roughness_factor;
    if (!o.normal.empty()) f.normal = o.normal;
    f.normal_scale = o.normal_scale;
    texels = load_material_texels(f, color);
  }
  const double decode_seconds = seconds_since(decode_start);
  if (o.stats < 0) throw input_error("--stats", "must be 0 or more texels per level");
  BrdfBuildOptions build;
  build.reduction.max_lobes = o.lobes;
  build.reduction.tolerance = o.tolerance;
  build.stats_samples = o.stats;
  std::vector<BrdfLevelStats> stats;
  const auto start = std::chrono::steady_clock::now();
  double brdf_seconds = 0;
  const MipData mip = build_mip(std::move(texels), build, o.stats > 0 ? &stats : nullptr, &brdf_seconds);
  const double seconds = seconds_since(start);
  const auto write_start = std::chrono::steady_clock::now();
  write_mip_file(o.out, mip);
  const double write_seconds = seconds_since(write_start);
  std::printf("%s: %dx%d, %d levels, up to %d lobes per texel (decoded in %.2f s, built in %.2f s, the BRDF pyramid %.2f s, "
              "written in %.2f s)\n",
              o.out.c_str(), mip.extent(0).width, mip.extent(0).height, mip.levels(), o.lobes, decode_seconds, seconds,
              brdf_seconds, write_seconds);
  if (o.stats > 0) {
    std::printf("level  lobes mean  slots  reduction e_rel mean  max   (against the union of the children's lobes, %d texels)\n", o.stats);
    for (std::size_t l = 1; l < stats.size(); ++l)
      std::printf("%-6zu %10.2f %6d %21.4f %6.4f\n", l, stats[l].mean_lobes, stats[l].max_lobes, stats[l].reduction_erel_mean,
                  stats[l].reduction_erel_max);
  }
}

struct EvalOptions {
  std::string file, mode;
  int level = -1;
  std::vector<int> texel;
  std::uint64_t max_texels = resource_limits().max_texels;
};

void run_eval(const EvalOptions& o) {
  // A mode is the reference `exact` or a filter that stores coarse texels (level0 stores none).
  const std::optional<TextureFilter> filter = parse_filter(o.mode);
  if (filter ? *filter == TextureFilter::level0 : o.mode != "exact")
    throw input_error("--mode", "unknown mode '" + o.mode + "' (exact, param, toksvig, vmf, brdf)");
  resource_limits().max_texels = o.max_texels;  // before the MIP file is read
  const MipData mip = read_mip_file(o.file);
  check_texel(mip, o.level, o.texel[0], o.texel[1]);
  const ExactReference reference(mip.level0);
  std::string line;
  long n = 0;
  while (std::getline(std::cin, line)) {
    ++n;
    glm::vec3 wi, wo;
    if (!parse_direction_line(line, n, wi, wo)) continue;
    const int i = o.texel[0], j = o.texel[1];
    const glm::dvec3 f = filter ? texel_eval(mip, *filter, o.level, i, j, glm::dvec3(wi), glm::dvec3(wo))
                                : reference.eval(o.level, i, j, glm::dvec3(wi), glm::dvec3(wo));
    std::printf("%.9g %.9g %.9g\n", f.r, f.g, f.b);
  }
}

struct CompareOptions_ {
  std::string file, levels;
  bool json = false;
  int subset = 256;
  std::uint64_t max_texels = resource_limits().max_texels;
};

// "a..b" or "a".
void parse_levels(const std::string& text, int& first, int& last) {
  const auto dots = text.find("..");
  try {
    std::size_t used = 0;
    if (dots == std::string::npos) {
      first = last = std::stoi(text, &used);
      if (used != text.size()) throw std::invalid_argument(text);
    } else {
      const std::string a = text.substr(0, dots), b = text.substr(dots + 2);
      first = std::stoi(a, &used);
      if (used != a.size()) throw std::invalid_argument(a);
      last = std::stoi(b, &used);
      if (used != b.size()) throw std::invalid_argument(b);
    }
  } catch (const std::exception&) {
    throw input_error("--levels", "'" + text + "' is not a level range like 1..5");
  }
}

void run_compare(const CompareOptions_& o) {
  if (o.subset < 1) throw input_error("--subset", "must be at least 1");
  resource_limits().max_texels = o.max_texels;  // before the MIP file is read
  const MipData mip = read_mip_file(o.file);
  CompareOptions c;
  c.subset = o.subset;
  c.first_level = std::min(1, mip.levels() - 1);
  c.last_level = mip.levels() - 1;
  if (!o.levels.empty()) parse_levels(o.levels, c.first_level, c.last_level);
  const std::vector<LevelComparison> rows = compare_levels(mip, c);
  const std::string text = o.json ? comparison_json(rows, o.subset, o.file) : comparison_table(rows, o.subset);
  std::fputs(text.c_str(), stdout);
}

}  // namespace

void add_mip_commands(CLI::App& app) {
  auto m = std::make_shared<MipOptions>();
  CLI::App* mip = app.add_subcommand("mip", "Build the BRDF pyramid (and the parameter pyramid) of a material into an OpenEXR MIP file");
  mip->add_option("SCENE", m->scene, "a glTF 2.0 file (.gltf or .glb) to take the material from (with --material), or "
                                      "alone: every material's MIP maps into the MIP cache that svbrdf-render reads");
  mip->add_option("--material", m->material, "the glTF material's name or index");
  mip->add_option("--base-color", m->base_color, "base color image (sRGB-encoded; float images are taken as linear)");
  mip->add_option("--base-color-factor", m->base_color_factor, "linear base color factor r,g,b in [0, 1] (multiplies the image)")
      ->delimiter(',')
      ->expected(3)
      ->check(cli::number_in(0.0, 1.0));
  mip->add_option("--normal", m->normal, "tangent-space normal map (+Y up, as glTF)");
  mip->add_option_function<float>("--normal-scale", [m](float s) { m->normal_scale = s, m->normal_scale_set = true; },
                                  "normal scale s: n = normalize((2·rgb − 1)·(s, s, 1)) (default 1)")
      ->check(cli::number_in(-kMaxNormalScale, kMaxNormalScale));
  mip->add_option("--metallic-roughness", m->metallic_roughness, "metallic-roughness image (G roughness, B metallic)");
  mip->add_option("--metallic-factor", m->metallic_factor, "metallic factor in [0, 1] (default 1)")->check(cli::number_in(0.0, 1.0));
  mip->add_option("--roughness-factor", m->roughness_factor, "roughness factor in [0, 1] (default 1)")->check(cli::number_in(0.0, 1.0));
  mip->add_option("--lobes", m->lobes, "most lobes per BRDF texel, 1.." + std::to_string(kMaxLobes) + " (default " +
                                           std::to_string(kDefaultLobes) + ")")
      ->check(cli::whole_in(1, kMaxLobes));
  mip->add_option("--tolerance", m->tolerance, "estimated relative error below which lobes merge even under --lobes, in [0, 1) "
                                               "(default 0.01)")
      ->check(cli::number_in(0.0, 1.0, false, true));
  mip->add_option("--stats", m->stats, "print per level the lobes used and the measured reduction error on N random texels")
      ->check(cli::whole_in(0, INT_MAX));
  add_max_texels_option(mip, m->max_texels);
  mip->add_option("--ocio-config", m->ocio_config, "OpenColorIO config to use instead of $OCIO or the built-in one");
  mip->add_option("--out", m->out, "the MIP file to write (.exr)");
  m->cache.add_to(mip);
  mip->callback([m] { run_mip(*m); });

  auto e = std::make_shared<EvalOptions>();
  CLI::App* eval = app.add_subcommand("eval", "Evaluate one texel's BRDF from a MIP file for direction pairs read from stdin");
  eval->add_option("FILE", e->file, "the MIP file")->required();
  eval->add_option("--level", e->level, "the MIP level")->required()->check(cli::whole_in(0, INT_MAX));
  eval->add_option("--texel", e->texel, "column I and row J (from the top)")->expected(2)->required()->check(cli::whole_in(0, INT_MAX));
  add_max_texels_option(eval, e->max_texels);
  eval->add_option("--mode", e->mode, "exact | param | toksvig | vmf | brdf")->required();
  eval->footer("Input: lines 'wi.x wi.y wi.z wo.x wo.y wo.z' (geometric tangent frame); output: 'r g b' per line.");
  eval->callback([e] { run_eval(*e); });

  auto c = std::make_shared<CompareOptions_>();
  CLI::App* cmp = app.add_subcommand("compare", "Per level, the error of param, the engine baselines and brdf against exact");
  cmp->add_option("FILE", c->file, "the MIP file")->required();
  cmp->add_option("--levels", c->levels, "levels a..b (default: 1 to the last)");
  cmp->add_flag("--json", c->json, "print JSON instead of a table");
  cmp->add_option("--subset", c->subset, "texels measured per level where a level has more (default 256, the spec's minimum)")
      ->check(cli::whole_in(1, INT_MAX));
  add_max_texels_option(cmp, c->max_texels);
  cmp->callback([c] { run_compare(*c); });
}

}  // namespace svbrdf
