// svbrdf-render: an Embree path tracer for textured glTF 2.0 scenes. A thin main: parse the command
// line, call the library, map errors to exit codes (2 bad input, 1 internal or environment failure,
// 130 for SIGINT and 143 for SIGTERM, after writing what had accumulated when the render had begun).
#include <CLI/CLI.hpp>

#include <cerrno>
#include <climits>
#include <csignal>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <tuple>
#include <utility>

#include "apps/baked_scenes.h"
#include "apps/mip_cache_options.h"
#include "apps/run_program.h"
#include "base/checked_number.h"
#include "base/cli_checks.h"
#include "base/error.h"
#include "base/interrupt.h"
#include "base/message_line.h"
#include "base/resource_limits.h"
#include "gltf/scene_reader.h"
#include "mip/texture_filter.h"
#include "render/output.h"
#include "render/progress.h"
#include "render/render_setup.h"
#include "render/renderer.h"
#include "textures/color.h"
#include "textures/image.h"

namespace {

namespace fs = std::filesystem;

// The most footprint scale --footprint-scale takes: a sample's texture footprint 64 times its pixel's
// reads MIP levels six steps coarser than the pixel's own. Scales above 1 are for experiments (the
// blur an engine's wider filter gives, a pyramid's coarse levels seen up close); past 64 the image is
// the texture's mean over most of the frame, no filter of the pixel any more, and a scale like 1e30
// only says that the value was mistyped.
constexpr double kMaxFootprintScale = 64.0;
// The most scattering events a path may have: the LOD recipes' own bound (scenes/lod_scenes.cpp). A
// path that long already carries nothing visible; a bound keeps a mistyped 10^9 from rendering
// mirrors facing each other for hours.
constexpr int kMaxDepth = 1024;
// ±64 stops scale the PNG by 2^±64: every pixel is black or white long before, and 2^128 would
// overflow a float.
constexpr double kMaxExposure = 64.0;

// "WxH" with both whole numbers ≥ 1 and no more than the image writer's side (kMaxImageSide), then
// within --max-texels and the memory budget at the film's bytes per pixel.
std::pair<int, int> parse_resolution(const std::string& text) {
  const svbrdf::Error bad = svbrdf::input_error("--res " + text, "expected WxH with whole numbers, e.g. 640x360");
  const std::size_t x = text.find_first_of("xX");
  if (x == std::string::npos) throw bad;
  long long side[2];
  const std::string parts[2] = {text.substr(0, x), text.substr(x + 1)};
  for (int i = 0; i < 2; ++i) {
    const char* begin = parts[i].c_str();
    char* end = nullptr;
    errno = 0;
    side[i] = std::strtoll(begin, &end, 10);
    if (end == begin || *end != '\0' || errno == ERANGE || parts[i].find_first_of("+- ") != std::string::npos) throw bad;
    if (side[i] < 1) throw svbrdf::input_error("--res " + text, "width and height must be at least 1");
    if (side[i] > svbrdf::kMaxImageSide)
      throw svbrdf::input_error("--res " + text, "a side of more than " + std::to_string(svbrdf::kMaxImageSide) +
                                                    " pixels is more than the image writer takes");
  }
  svbrdf::check_image_size(std::uint64_t(side[0]), std::uint64_t(side[1]), svbrdf::Film::kBytesPerPixel, "--res " + text);
  return {static_cast<int>(side[0]), static_cast<int>(side[1])};
}

// The showcase scene as the build places it, or as it is installed; the first that exists wins.
fs::path find_showcase(const char* argv0) {
  for (const char* relative : {"showcase/showcase.gltf", "showcase.gltf"})
    if (const auto found = svbrdf::find_baked_scene(argv0, relative)) return *found;
  // The program's name is the line's prefix already (main); the message names the file it looked for.
  throw svbrdf::input_error((svbrdf::baked_scene_folders(argv0).front() / "showcase" / "showcase.gltf").string(),
                            "no scene given, and the showcase scene has not been built here; pass a glTF file, "
                            "or build it (make render)");
}

// "the 16 samples per pixel", or "the 16 to 32 samples per pixel" for a render stopped within a pass
// (renderer.h), with the count asked for.
std::string samples_text(const svbrdf::RenderStats& stats, int spp) {
  std::string text = "the " + std::to_string(stats.pixel_samples_min);
  if (stats.pixel_samples_max != stats.pixel_samples_min) text += " to " + std::to_string(stats.pixel_samples_max);
  return text + " samples per pixel that had accumulated, of " + std::to_string(spp);
}

}  // namespace

int main(int argc, char** argv) {
  // First of all: a Ctrl-C or SIGTERM while the command line is read, the scene loaded or the MIP
  // chains and the BVH built ends the run at once with one line and exit 130 / 143. That work runs
  // inside libraries that cannot poll a flag, so the handler exits itself (base/interrupt.h); there
  // is nothing to keep yet. Once the render begins, the first signal stops it and what accumulated is
  // written.
  svbrdf::install_interrupt_handlers("svbrdf-render");
  svbrdf::set_interrupt_mode(svbrdf::InterruptMode::exit_now, " before the render began; nothing written");

  CLI::App app{"svbrdf-render: path-trace a textured glTF 2.0 scene"};
  std::string scene_file, out = "", png, res, camera, env, sun, filter = "brdf", light_sampling = "mis", ocio,
      light_units = "photometric", normal_mapping = "shading", variant, display, view;
  int spp = 64, threads = 0, max_depth = 16;
  std::uint64_t seed = 0, max_texels = svbrdf::resource_limits().max_texels;
  double time_limit = 0.0;
  float exposure = 0.0f, footprint_scale = 0.0f, clamp = 0.0f, aperture = 0.0f, focus_distance = 0.0f;
  bool use_float = false, quiet = false, aovs = false, transparent = false;
  app.add_option("scene", scene_file, "glTF file (.gltf or .glb); none renders the project's showcase scene");
  app.add_option("-o,--out", out, "output OpenEXR file (linear radiance); default out/<scene>.exr");
  app.add_option("--png", png, "display PNG (default: beside the EXR, same stem)");
  app.add_option("--spp", spp, "samples per pixel")->check(svbrdf::cli::whole_in(1, INT_MAX));
  app.add_option("--res", res, "resolution WxH (default: the camera's aspect at 360 rows, else 640x360)");
  app.add_option("--camera", camera, "camera index or name (default: the scene's first, else a framing camera)");
  app.add_option("--seed", seed, "random seed")->check(svbrdf::cli::unsigned_whole);
  app.add_option("--threads", threads, "worker threads (0: all cores; more than the machine runs at once are capped)")
      ->check(svbrdf::cli::whole_in(0, INT_MAX));
  app.add_option("--max-depth", max_depth, "maximum number of scattering events (0.." + std::to_string(kMaxDepth) + ")")
      ->check(svbrdf::cli::whole_in(0, kMaxDepth));
  app.add_option("--time-limit", time_limit,
                 "stop after this many seconds (once every pixel has a sample) and write what accumulated, exit 0")
      ->check(svbrdf::cli::non_negative);
  app.add_option("--max-texels", max_texels,
                 "the most texels one image may have: a texture, a MIP level, the frame (default 2^26 = 8192x8192; "
                 "at most 2^40)")
      ->check(svbrdf::cli::whole_in(1, svbrdf::cli::kMaxTexelsOption));
  app.add_option("--env", env, "environment: r,g,b radiance or an equirectangular HDR/EXR file "
                               "(default: white 1 when the scene has no lights, none when it has)");
  app.add_option("--sun", sun, "add a directional light: elevation,azimuth[,irradiance] (degrees, W/m^2)");
  app.add_option("--light-units", light_units,
                 "how the file's KHR_lights_punctual intensities are read: photometric (the specification's lux and "
                 "candela, divided by 683 lm/W) | radiometric (W/m^2 and W/sr as written)")
      ->check(CLI::IsMember({"photometric", "radiometric"}));
  app.add_option("--variant", variant,
                 "KHR_materials_variants: the material variant to render (default: each primitive's own material)");
  const std::vector<std::string> filters = svbrdf::filter_names();
  std::string filter_help = "texture filter:";
  for (const std::string& f : filters) filter_help += (f == filters.front() ? " " : " | ") + f;
  filter_help += " (default brdf: the BRDF-averaged MIP; level0: the nearest texel, no MIP, the ground truth at many spp)";
  app.add_option("--filter", filter, filter_help)->check(CLI::IsMember(filters));
  app.add_option("--footprint-scale", footprint_scale,
                 "each camera sample's texture footprint as a fraction of its pixel's, in (0, 64] (default 1/sqrt(spp), "
                 "its share of the pixel; pbrt-v4 uses max(1/8, 1/sqrt(spp)); 1: the whole pixel)")
      ->check(svbrdf::cli::number_in(0.0, kMaxFootprintScale, true, false));
  app.add_option("--light-sampling", light_sampling, "environment sampling: mis | nee | bsdf")
      ->check(CLI::IsMember({"mis", "nee", "bsdf"}));
  app.add_option("--normal-mapping", normal_mapping,
                 "how normal maps shade: shading (the mapped normal, turned toward the viewer where it faces away; "
                 "dark where it turns from a light, as in Cycles; the default) | microfacet (Schuessler et al. 2017: "
                 "never black where the surface is lit, energy kept, strong maps flattened under low light)")
      ->check(CLI::IsMember({"shading", "microfacet"}));
  app.add_option("--clamp", clamp,
                 "cap on the radiance one indirect light sample brings back, per channel (0: off, the default; "
                 "removes fireflies at the cost of bias)")
      ->check(svbrdf::cli::non_negative);
  app.add_option("--aperture", aperture,
                 "depth of field: the thin lens's radius in scene units (metres in glTF), in [0, 1e15] (default 0, "
                 "glTF's pinhole: glTF cameras carry no aperture)")
      ->check(svbrdf::cli::number_in(0.0, svbrdf::Camera::kMaxLensLength));
  app.add_option("--focus-distance", focus_distance,
                 "depth of field: the distance along the view axis that is sharp, in (0, 1e15] (default: that of the "
                 "first surface the ray through the frame's centre meets, else of the scene's centre)")
      ->check(svbrdf::cli::number_in(0.0, svbrdf::Camera::kMaxLensLength, true));
  app.add_option("--exposure", exposure, "exposure in stops for the PNG, in [-64, 64] (the EXR is never scaled)")
      ->check(svbrdf::cli::number_in(-kMaxExposure, kMaxExposure));
  app.add_option("--ocio-config", ocio, "OpenColorIO config for texture decoding and the PNG (default: $OCIO, else the built-in one)");
  app.add_option("--display", display, "the OCIO display the PNG is encoded for (default: the config's default display)");
  app.add_option("--view", view,
                 "the OCIO view of that display the PNG shows, e.g. Standard or Filmic in Blender's config (default: "
                 "the display's default view; the EXR is always scene-linear)");
  svbrdf::MipCacheOptions mip_cache_options;
  mip_cache_options.add_to(&app);
  app.add_flag("--float", use_float, "write 32-bit float EXR (default half)");
  app.add_flag("--transparent", transparent,
               "a transparent background: the camera does not see the environment (which still lights the scene), "
               "so the EXR's alpha is what the scene covers of each pixel, and the PNG has alpha too");
  app.add_flag("--aov", aovs, "also write the albedo, normal, depth and MIP level, as layers of the EXR (albedo.R/G/B, N.X/Y/Z, Z, mip_level.X)");
  app.add_flag("-q,--quiet", quiet, "no progress output or notes (warnings and errors are still printed)");
  return svbrdf::run_program("svbrdf-render", app, argc, argv, [&] {
    // Before any input is read: every image, MIP level and the frame are held to it.
    svbrdf::resource_limits().max_texels = max_texels;
    threads = svbrdf::cli::capped_threads(threads, "svbrdf-render");
    const svbrdf::TextureFilter texture_filter = *svbrdf::parse_filter(filter);
    svbrdf::SceneSetup setup;
    setup.camera = camera;
    setup.env = env;
    setup.sun = sun;
    setup.filter = texture_filter;
    setup.aperture = aperture;
    setup.focus_distance = focus_distance;
    if (!res.empty()) std::tie(setup.width, setup.height) = parse_resolution(res);
    const fs::path scene_path = scene_file.empty() ? find_showcase(argv[0]) : fs::path(scene_file);
    // The showcase is lit by a sun and its sky; glTF has no ratified way to carry an environment, so
    // the recipe bakes the sky beside the scene and the default render uses it unless --env says else.
    if (scene_file.empty() && env.empty() && fs::exists(scene_path.parent_path() / "sky.hdr"))
      setup.env = (scene_path.parent_path() / "sky.hdr").string();
    if (out.empty()) out = (fs::path("out") / scene_path.stem()).string() + ".exr";
    if (fs::path(out).extension() != ".exr") throw svbrdf::input_error("--out " + out, "the output must be an .exr file");

    svbrdf::OutputOptions oo;
    oo.exr = out;
    oo.png = png;
    oo.float32 = use_float;
    oo.exposure = exposure;
    oo.aovs = aovs;
    oo.transparent = transparent;
    // Before the scene is read: a render must not end in "cannot write" for a path that was wrong
    // from the start. Also removes the temporaries a killed run left there.
    svbrdf::prepare_outputs(oo);

    const svbrdf::ColorConfig color =
        svbrdf::ColorConfig::resolve(ocio.empty() ? std::nullopt : std::optional<fs::path>(ocio));
    // Before the scene is read: a display or view the config lacks is refused at once.
    std::tie(oo.display, oo.view) = color.display_view(display, view);
    svbrdf::LoadOptions load;
    load.light_units = light_units == "radiometric" ? svbrdf::LightUnits::radiometric : svbrdf::LightUnits::photometric;
    load.variant = variant;
    svbrdf::SetupProgress setup_progress("svbrdf-render", quiet);
    setup.progress = &setup_progress;
    // The brdf filter's builds are the ones worth keeping (render/mip_cache.h).
    const std::unique_ptr<svbrdf::MipCache> mip_cache =
        texture_filter == svbrdf::TextureFilter::brdf ? mip_cache_options.open("svbrdf-render") : nullptr;
    setup.mip_cache = mip_cache.get();
    setup_progress.begin("reading " + scene_path.filename().string() + " and decoding its images");
    svbrdf::Scene scene = svbrdf::load_gltf(scene_path, load);
    setup_progress.end();
    for (const std::string& w : scene.warnings)
      std::fprintf(stderr, "svbrdf-render: warning: %s\n", svbrdf::message_line(w).c_str());
    const svbrdf::PreparedScene prepared(std::move(scene), setup, color);
    svbrdf::print_mip_cache_warnings(mip_cache.get(), "svbrdf-render");
    if (const auto counts = prepared.mip_cache_counts(); !quiet && counts.read + counts.built > 0)
      std::fprintf(stderr, "svbrdf-render: MIP maps: %d read from the MIP cache %s, %d built\n", counts.read,
                   svbrdf::message_line(mip_cache->folder().string()).c_str(), counts.built);
    // glTF carries no environment: whichever one lights the render is said, once (a note, not a
    // warning: --quiet silences it with the progress).
    if (!quiet && !prepared.environment_note().empty())
      std::fprintf(stderr, "svbrdf-render: environment: %s\n", svbrdf::message_line(prepared.environment_note()).c_str());
    if (!quiet && prepared.camera().has_lens())
      std::fprintf(stderr, "svbrdf-render: depth of field: a lens of radius %g focused at %g along the view axis%s\n",
                   double(prepared.camera().lens_radius()), double(prepared.camera().focus_distance()),
                   focus_distance > 0.0f ? "" : " (autofocus on the frame's centre)");
    for (const std::string& w : prepared.warnings())
      std::fprintf(stderr, "svbrdf-render: warning: %s\n", svbrdf::message_line(w).c_str());
    for (const std::string& w : prepared.mip_warnings(texture_filter))
      std::fprintf(stderr, "svbrdf-render: warning: %s\n", svbrdf::message_line(w).c_str());
    const std::uint64_t pixels = std::uint64_t(prepared.camera().width()) * std::uint64_t(prepared.camera().height());
    // The sample counters are 64-bit: spp × pixels must fit (it does unless --max-texels is huge).
    if (const auto total = svbrdf::checked_mul(pixels, std::uint64_t(spp)); !total || *total >= (std::uint64_t(1) << 63))
      throw svbrdf::input_error("--spp " + std::to_string(spp), "with " + std::to_string(pixels) +
                                                                     " pixels, more samples than a 63-bit counter holds");

    svbrdf::RenderOptions options;
    options.spp = spp;
    options.threads = threads;
    options.seed = seed;
    options.time_limit = time_limit;
    options.integrator.max_depth = max_depth;
    options.integrator.filter = texture_filter;
    options.integrator.footprints = aovs;  // the MIP-level AOV; the MIP filters compute their own
    options.integrator.footprint_scale = footprint_scale;  // 0: resolved to 1/√spp by render()
    options.integrator.clamp = clamp;
    options.integrator.normal_mapping =
        normal_mapping == "microfacet" ? svbrdf::NormalMapping::microfacet : svbrdf::NormalMapping::shading;
    options.aovs = aovs;
    options.integrator.background = !transparent;
    options.integrator.light_sampling = light_sampling == "nee"    ? svbrdf::LightSampling::nee
                                        : light_sampling == "bsdf" ? svbrdf::LightSampling::bsdf
                                                                   : svbrdf::LightSampling::mis;
    options.cancel = &svbrdf::interrupt_requested();
    setup_progress.end();
    svbrdf::ProgressPrinter printer(quiet);
    options.progress = [&](const svbrdf::ProgressInfo& p) { printer.update(p); };
    // The first signal stops the render, which then writes what accumulated; a second one exits at
    // once for a user who does not want to wait.
    svbrdf::set_interrupt_mode(svbrdf::InterruptMode::stop_once, " a second time; the render was abandoned, nothing written");
    svbrdf::RenderStats stats;
    const svbrdf::Film film = svbrdf::render(prepared.world(), options, &stats);
    // Writing the EXR and the PNG is short and must not be cut between the two: signals now only
    // change the exit status.
    svbrdf::set_interrupt_mode(svbrdf::InterruptMode::record);
    printer.finish({stats.samples, pixels * std::uint64_t(spp), stats.rays, stats.seconds});

    svbrdf::write_outputs(film, oo, color);
    if (!quiet) std::fprintf(stderr, "svbrdf-render: wrote %s\n", out.c_str());
    if (const int sig = svbrdf::interrupt_signal()) {
      std::fprintf(stderr, "svbrdf-render: %s; wrote %s\n", sig == SIGTERM ? "terminated (SIGTERM)" : "interrupted (SIGINT)",
                   samples_text(stats, spp).c_str());
      return 128 + sig;
    }
    // Stopped early by the budget the user set: not a failure (exit 0), but the image has fewer
    // samples than asked for, which --quiet must not hide.
    if (stats.timed_out && stats.pixel_samples_min < std::uint32_t(spp))
      std::fprintf(stderr, "svbrdf-render: stopped at the time limit (%g s); wrote %s\n", time_limit, samples_text(stats, spp).c_str());
    return 0;
  });
}
