#include "apps/render_command.h"

#include <cerrno>
#include <climits>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <tuple>
#include <utility>

#include "apps/render_frames.h"
#include "base/checked_number.h"
#include "base/cli_checks.h"
#include "base/error.h"
#include "base/interrupt.h"
#include "base/message_line.h"
#include "gltf/scene_reader.h"
#include "mip/texture_filter.h"
#include "render/crop.h"
#include "render/output.h"
#include "render/progress.h"
#include "render/render_setup.h"
#include "textures/color.h"
#include "textures/image.h"

namespace svbrdf {

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
  const Error bad = input_error("--res " + text, "expected WxH with whole numbers, e.g. 640x360");
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
    if (side[i] < 1) throw input_error("--res " + text, "width and height must be at least 1");
    if (side[i] > kMaxImageSide)
      throw input_error("--res " + text, "a side of more than " + std::to_string(kMaxImageSide) +
                                                    " pixels is more than the image writer takes");
  }
  check_image_size(std::uint64_t(side[0]), std::uint64_t(side[1]), Film::kBytesPerPixel, "--res " + text);
  return {static_cast<int>(side[0]), static_cast<int>(side[1])};
}

// "the 16 samples per pixel", or "the 16 to 32 samples per pixel" for a render stopped within a pass
// (renderer.h), with the count asked for.
std::string samples_text(const RenderStats& stats, int spp) {
  std::string text = "the " + std::to_string(stats.pixel_samples_min);
  if (stats.pixel_samples_max != stats.pixel_samples_min) text += " to " + std::to_string(stats.pixel_samples_max);
  return text + " samples per pixel that had accumulated, of " + std::to_string(spp);
}

// Renders one frame (or a tile of it) of `world` and writes it to `oo` when command.out is set: the
// render's progress, its stop on a signal, and what it says of how it ended.
RenderOutcome render_and_write(const RenderCommand& c, const RenderWorld& world, RenderOptions options,
                               const OutputOptions& oo, const ColorConfig& color, const TextureTiles* tiles,
                               const char* program) {
  const bool write = !c.out.empty(), tile = oo.tile;
  const std::uint64_t pixels = std::uint64_t(options.crop.width()) * std::uint64_t(options.crop.height());
  ProgressPrinter printer(c.quiet);
  options.progress = [&](const ProgressInfo& p) { printer.update(p); };
  // The first signal stops the render, which then writes what accumulated; a second one exits at
  // once for a user who does not want to wait.
  set_interrupt_mode(InterruptMode::stop_once, " a second time; the render was abandoned, nothing written");
  RenderOutcome outcome;
  outcome.film = render(world, options, &outcome.stats);
  const RenderStats& stats = outcome.stats;
  // A tile the texture cache could not read was shaded as zeros: nothing is written.
  if (tiles)
    if (const std::string failure = tiles->failure(); !failure.empty()) throw environment_error("--texture-cache", failure);
  // Writing the EXR and the PNG is short and must not be cut between the two: signals now only
  // change the exit status.
  set_interrupt_mode(InterruptMode::record);
  printer.finish({stats.samples, pixels * std::uint64_t(c.spp), stats.rays, stats.seconds});

  // A tile stopped early holds fewer samples than the whole render's pixels: it is not written, so
  // that no merge can take it (a requeued task renders it again).
  const bool keep = write && !(tile && stats.pixel_samples_min < std::uint32_t(c.spp));
  if (keep) {
    write_outputs(outcome.film, oo, color);
    if (!c.quiet) std::fprintf(stderr, "%s: wrote %s\n", program, oo.exr.string().c_str());
  }
  const char* what = keep ? "wrote" : write ? "wrote nothing (a tile is written whole or not at all): rendered" : "rendered";
  if (const int sig = interrupt_signal()) {
    std::fprintf(stderr, "%s: %s; %s %s\n", program, sig == SIGTERM ? "terminated (SIGTERM)" : "interrupted (SIGINT)", what,
                 samples_text(stats, c.spp).c_str());
    outcome.status = 128 + sig;
  } else if (stats.timed_out && stats.pixel_samples_min < std::uint32_t(c.spp)) {
    // Stopped early by the budget the user set: not a failure (exit 0), but the image has fewer
    // samples than asked for, which --quiet must not hide.
    std::fprintf(stderr, "%s: stopped at the time limit (%g s); %s %s\n", program, c.time_limit, what,
                 samples_text(stats, c.spp).c_str());
  }
  return outcome;
}

}  // namespace

void RenderCommand::add_options(CLI::App& app) {
  app.add_option("scene", scene_file, "glTF file (.gltf or .glb); none renders the project's showcase scene");
  app.add_option("tiles", more_inputs, "with --merge: the tiles (the first stands where the scene does)");
  app.add_option("-o,--out", out, "output OpenEXR file (linear radiance); default out/<scene>.exr");
  app.add_option("--png", png, "display PNG (default: beside the EXR, same stem)");
  app.add_option("--spp", spp, "samples per pixel")->check(cli::whole_in(1, INT_MAX));
  app.add_option("--res", res, "resolution WxH (default: the camera's aspect at 360 rows, else 640x360)");
  app.add_option("--crop", crop,
                 "render only the window x0,y0,x1,y1 of the frame (pixels, columns [x0, x1), rows [y0, y1)): its EXR "
                 "alone, in float, placed in the frame (data and display windows), each pixel that of the whole "
                 "render; for --merge");
  app.add_option("--tile", tile,
                 "render only tile I of N (I from 0 to N-1): the frame cut into N bands of whole rows, band I the rows "
                 "[floor(I*H/N), floor((I+1)*H/N)); written as --crop writes, for --merge");
  app.add_option("--frames", frames,
                 "render frames A to B (A-B) or frame N of the camera's glTF animation, frame f at time f/fps seconds, "
                 "each to its own files: a run of # in the --out name becomes the zero-padded frame number "
                 "(out.####.exr: out.0012.exr), else the number goes before the extension (out.exr: out.0012.exr); "
                 "--png likewise");
  app.add_option("--fps", fps, "with --frames: frames per second (default 24), in (0, 1e6]")
      ->check(cli::number_in(0.0, 1e6, true));
  app.add_option("--camera", camera, "camera index or name (default: the scene's first, else a framing camera)");
  app.add_option("--seed", seed, "random seed")->check(cli::unsigned_whole);
  app.add_option("--threads", threads, "worker threads (0: all cores; more than the machine runs at once are capped)")
      ->check(cli::whole_in(0, INT_MAX));
  app.add_option("--max-depth", max_depth, "maximum number of scattering events (0.." + std::to_string(kMaxDepth) + ")")
      ->check(cli::whole_in(0, kMaxDepth));
  app.add_option("--time-limit", time_limit,
                 "stop after this many seconds (once every pixel has a sample) and write what accumulated, exit 0")
      ->check(cli::non_negative);
  app.add_option("--max-texels", max_texels,
                 "the most texels one image may have: a texture, a MIP level, the frame (default 2^26 = 8192x8192; "
                 "at most 2^40)")
      ->check(cli::whole_in(1, cli::kMaxTexelsOption));
  app.add_option("--env", env, "environment: r,g,b radiance or an equirectangular HDR/EXR file "
                               "(default: white 1 when the scene has no lights, none when it has)");
  app.add_option("--sun", sun, "add a directional light: elevation,azimuth[,irradiance] (degrees, W/m^2)");
  app.add_option("--light-units", light_units,
                 "how the file's KHR_lights_punctual intensities are read: photometric (the specification's lux and "
                 "candela, divided by 683 lm/W) | radiometric (W/m^2 and W/sr as written)")
      ->check(CLI::IsMember({"photometric", "radiometric"}));
  app.add_option("--variant", variant,
                 "KHR_materials_variants: the material variant to render (default: each primitive's own material)");
  const std::vector<std::string> filters = filter_names();
  std::string filter_help = "texture filter:";
  for (const std::string& f : filters) filter_help += (f == filters.front() ? " " : " | ") + f;
  filter_help += " (default brdf: the BRDF-averaged MIP; level0: the nearest texel, no MIP, the ground truth at many spp)";
  app.add_option("--filter", filter, filter_help)->check(CLI::IsMember(filters));
  app.add_option("--footprint-scale", footprint_scale,
                 "each camera sample's texture footprint as a fraction of its pixel's, in (0, 64] (default 1/sqrt(spp), "
                 "its share of the pixel; pbrt-v4 uses max(1/8, 1/sqrt(spp)); 1: the whole pixel)")
      ->check(cli::number_in(0.0, kMaxFootprintScale, true, false));
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
      ->check(cli::non_negative);
  app.add_option("--aperture", aperture,
                 "depth of field: the thin lens's radius in scene units (metres in glTF), in [0, 1e15] (default 0, "
                 "glTF's pinhole: glTF cameras carry no aperture)")
      ->check(cli::number_in(0.0, Camera::kMaxLensLength));
  app.add_option("--focus-distance", focus_distance,
                 "depth of field: the distance along the view axis that is sharp, in (0, 1e15] (default: that of the "
                 "first surface the ray through the frame's centre meets, else of the scene's centre)")
      ->check(cli::number_in(0.0, Camera::kMaxLensLength, true));
  app.add_option("--exposure", exposure, "exposure in stops for the PNG, in [-64, 64] (the EXR is never scaled)")
      ->check(cli::number_in(-kMaxExposure, kMaxExposure));
  app.add_option("--ocio-config", ocio, "OpenColorIO config for texture decoding and the PNG (default: $OCIO, else the built-in one)");
  app.add_option("--display", display, "the OCIO display the PNG is encoded for (default: the config's default display)");
  app.add_option("--view", view,
                 "the OCIO view of that display the PNG shows, e.g. Standard or Filmic in Blender's config (default: "
                 "the display's default view; the EXR is always scene-linear)");
  mip_cache.add_to(&app);
  app.add_option("--texture-cache", texture_cache,
                 "read the textures out of core: written once as tiled files in the MIP cache's folder and read "
                 "through a cache of at most MB megabytes (10^6 bytes), at least " +
                     std::to_string(int(TextureTiles::kMinMegabytes)) + " (MB left out: " +
                     std::to_string(int(TextureTiles::kDefaultMegabytes)) + "; default: the images held in memory whole)")
      ->expected(0, 1);
  app.add_flag("--float", use_float, "write 32-bit float EXR (default half)");
  app.add_flag("--transparent", transparent,
               "a transparent background: the camera does not see the environment (which still lights the scene), "
               "so the EXR's alpha is what the scene covers of each pixel, and the PNG has alpha too");
  app.add_flag("--aov", aovs, "also write the albedo, normal, depth and MIP level, as layers of the EXR (albedo.R/G/B, N.X/Y/Z, Z, mip_level.X)");
  app.add_flag("-q,--quiet", quiet, "no progress output or notes (warnings and errors are still printed)");
}

std::optional<double> texture_cache_megabytes(const std::optional<std::string>& text) {
  if (!text) return std::nullopt;
  if (text->empty()) return TextureTiles::kDefaultMegabytes;
  double mb = 0.0;
  std::size_t used = 0;
  try {
    mb = std::stod(*text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == 0 || used != text->size() || !(mb >= TextureTiles::kMinMegabytes && mb <= 1e9))
    throw input_error("--texture-cache " + *text, "expected megabytes, a number in [" +
                                                      std::to_string(int(TextureTiles::kMinMegabytes)) +
                                                      ", 1e9] (OpenImageIO's image cache keeps at least 10 MB)");
  return mb;
}

OutputOptions RenderCommand::output_options() const {
  if (!out.empty() && fs::path(out).extension() != ".exr") throw input_error("--out " + out, "the output must be an .exr file");
  OutputOptions oo;
  oo.exr = out;
  oo.png = png;
  oo.float32 = use_float;
  oo.exposure = exposure;
  oo.aovs = aovs;
  oo.transparent = transparent;
  oo.tile = !crop.empty() || !tile.empty();
  return oo;
}

RenderOutcome run_render(RenderCommand& c, const fs::path& scene_path, const char* program,
                         const std::atomic<bool>& cancel) {
  // Before any input is read: every image, MIP level and the frame are held to it.
  resource_limits().max_texels = c.max_texels;
  const int threads = cli::capped_threads(c.threads, program);
  const TextureFilter texture_filter = *parse_filter(c.filter);
  SceneSetup setup;
  setup.camera = c.camera;
  setup.env = c.env;
  setup.sun = c.sun;
  setup.filter = texture_filter;
  setup.aperture = c.aperture;
  setup.focus_distance = c.focus_distance;
  if (!c.res.empty()) std::tie(setup.width, setup.height) = parse_resolution(c.res);
  // The showcase is lit by a sun and its sky; glTF has no ratified way to carry an environment, so
  // the recipe bakes the sky beside the scene and the default render uses it unless --env says else.
  if (c.scene_file.empty() && c.env.empty() && fs::exists(scene_path.parent_path() / "sky.hdr"))
    setup.env = (scene_path.parent_path() / "sky.hdr").string();
  if (!c.more_inputs.empty())
    throw input_error(c.more_inputs.front(), "a second scene: svbrdf-render renders one (--merge takes tiles)");
  const bool write = !c.out.empty();
  OutputOptions oo = c.output_options();
  const bool tile = oo.tile;
  if (!c.crop.empty() && !c.tile.empty())
    throw input_error("--crop " + c.crop, "and --tile " + c.tile + " both name the part to render; give one");
  // A tile must hold, pixel for pixel, what the whole frame's render holds (render/crop.h); a clock
  // would stop each machine at other sample counts.
  if (tile && c.time_limit > 0.0)
    throw input_error("--time-limit", "a tile is rendered whole, to every sample asked for, so that the merged "
                                      "image is the single render's; leave out --time-limit with --crop or --tile");
  if (tile && !c.png.empty())
    throw input_error("--png " + c.png, "a tile (--crop, --tile) is written as its EXR alone; --merge writes the PNG");

  if (c.fps != 0.0 && c.frames.empty()) throw input_error("--fps", "sets the rate of --frames; give --frames too");
  const std::optional<FrameRange> range = c.frames.empty() ? std::nullopt : std::optional(parse_frames(c.frames));
  const double fps = c.fps > 0.0 ? c.fps : kDefaultFps;
  // Frame f's outputs (apps/render_frames.h).
  const auto frame_outputs = [&](int f) {
    OutputOptions o = oo;
    o.exr = frame_path(c.out, f, "--out");
    if (!c.png.empty()) o.png = frame_path(c.png, f, "--png");
    return o;
  };

  // Before the scene is read: a render must not end in "cannot write" for a path that was wrong
  // from the start. Also removes the temporaries a killed run left there.
  // The first frame's here, each further frame's before it renders.
  if (write) prepare_outputs(range ? frame_outputs(range->first) : oo);

  const ColorConfig color = ColorConfig::resolve(c.ocio.empty() ? std::nullopt : std::optional<fs::path>(c.ocio));
  // Before the scene is read: a display or view the config lacks is refused at once.
  std::tie(oo.display, oo.view) = color.display_view(c.display, c.view);
  LoadOptions load;
  load.light_units = c.light_units == "radiometric" ? LightUnits::radiometric : LightUnits::photometric;
  load.variant = c.variant;
  load.camera_animation = range.has_value();
  SetupProgress setup_progress(program, c.quiet);
  setup.progress = &setup_progress;
  // The brdf filter's builds are the ones worth keeping (render/mip_cache.h).
  const std::unique_ptr<MipCache> mip_cache = texture_filter == TextureFilter::brdf ? c.mip_cache.open(program) : nullptr;
  setup.mip_cache = mip_cache.get();
  // Out of core: each image goes to the texture cache's files as it is decoded (render/texture_tiles.h).
  std::unique_ptr<TextureTiles> tiles;
  if (const std::optional<double> mb = texture_cache_megabytes(c.texture_cache)) {
    const std::unique_ptr<MipCache> folder = c.mip_cache.open(program);
    if (!folder)
      throw input_error("--texture-cache", "its files live in the MIP cache's folder, and there is none (--mip-cache DIR names one)");
    tiles = std::make_unique<TextureTiles>(folder->folder(), *mb);
    load.take_image = [&](std::size_t index, ImageDesc& image, bool is_color) {
      TextureSet::store(index, image, is_color, color, *tiles);
    };
    // An image whose files an earlier render wrote is not decoded.
    load.find_image = [&](std::size_t index, ImageDesc& image, bool is_color) {
      return TextureSet::find(index, image, is_color, color, *tiles);
    };
    setup.texture_tiles = tiles.get();
  }
  setup_progress.begin("reading " + scene_path.filename().string() + " and decoding its images");
  Scene scene = load_gltf(scene_path, load);
  setup_progress.end();
  for (const std::string& w : scene.warnings) std::fprintf(stderr, "%s: warning: %s\n", program, message_line(w).c_str());
  if (tiles)
    for (const std::string& w : tiles->warnings()) std::fprintf(stderr, "%s: warning: %s\n", program, message_line(w).c_str());
  PreparedScene prepared(std::move(scene), setup, color);
  // Every frame's pose checked before the first renders; the notes below are the first frame's.
  if (range) {
    check_frame_poses(prepared.camera_desc(), *range, fps, scene_path.string());
    prepared.pose_camera(frame_pose(prepared.camera_desc(), range->first, fps));
  }
  print_mip_cache_warnings(mip_cache.get(), program);
  if (const auto counts = prepared.mip_cache_counts(); !c.quiet && counts.read + counts.built > 0)
    std::fprintf(stderr, "%s: MIP maps: %d read from the MIP cache %s, %d built\n", program, counts.read,
                 message_line((mip_cache ? mip_cache->folder() : tiles->folder()).string()).c_str(),
                 counts.built);
  if (tiles && !c.quiet)
    std::fprintf(stderr,
                 "%s: texture cache: %d files in %s (images: %d decoded, %d found there), %.1f MB of texels, at most %.1f MB "
                 "of them in memory\n",
                 program, tiles->file_count(), message_line(tiles->folder().string()).c_str(), tiles->image_counts().decoded,
                 tiles->image_counts().found, double(tiles->texel_bytes()) / 1e6, *texture_cache_megabytes(c.texture_cache));
  // glTF carries no environment: whichever one lights the render is said, once (a note, not a
  // warning: --quiet silences it with the progress).
  if (!c.quiet && !prepared.environment_note().empty())
    std::fprintf(stderr, "%s: environment: %s\n", program, message_line(prepared.environment_note()).c_str());
  if (!c.quiet && prepared.camera().has_lens())
    std::fprintf(stderr, "%s: depth of field: a lens of radius %g focused at %g along the view axis%s\n", program,
                 double(prepared.camera().lens_radius()), double(prepared.camera().focus_distance()),
                 c.focus_distance > 0.0f ? "" : " (autofocus on the frame's centre)");
  for (const std::string& w : prepared.warnings()) std::fprintf(stderr, "%s: warning: %s\n", program, message_line(w).c_str());
  for (const std::string& w : prepared.mip_warnings(texture_filter))
    std::fprintf(stderr, "%s: warning: %s\n", program, message_line(w).c_str());
  const int frame_w = prepared.camera().width(), frame_h = prepared.camera().height();
  const PixelRect crop = !c.crop.empty()  ? parse_crop(c.crop, frame_w, frame_h)
                         : !c.tile.empty() ? parse_tile(c.tile, frame_w, frame_h)
                                           : PixelRect{0, 0, frame_w, frame_h};
  const std::uint64_t pixels = std::uint64_t(crop.width()) * std::uint64_t(crop.height());
  // The sample counters are 64-bit: spp × pixels must fit (it does unless --max-texels is huge).
  if (const auto total = checked_mul(pixels, std::uint64_t(c.spp)); !total || *total >= (std::uint64_t(1) << 63))
    throw input_error("--spp " + std::to_string(c.spp),
                      "with " + std::to_string(pixels) + " pixels, more samples than a 63-bit counter holds");

  RenderOptions options;
  options.spp = c.spp;
  options.threads = threads;
  options.seed = c.seed;
  options.crop = crop;
  options.time_limit = c.time_limit;
  options.integrator.max_depth = c.max_depth;
  options.integrator.filter = texture_filter;
  options.integrator.footprints = c.aovs;  // the MIP-level AOV; the MIP filters compute their own
  options.integrator.footprint_scale = c.footprint_scale;  // 0: resolved to 1/√spp by render()
  options.integrator.clamp = c.clamp;
  options.integrator.normal_mapping = c.normal_mapping == "microfacet" ? NormalMapping::microfacet : NormalMapping::shading;
  options.aovs = c.aovs;
  options.integrator.background = !c.transparent;
  options.integrator.light_sampling = c.light_sampling == "nee"    ? LightSampling::nee
                                      : c.light_sampling == "bsdf" ? LightSampling::bsdf
                                                                   : LightSampling::mis;
  options.cancel = &cancel;
  setup_progress.end();
  if (!range) return render_and_write(c, prepared.world(), options, oo, color, tiles.get(), program);
  RenderOutcome outcome;
  for (int f = range->first;; ++f) {
    // A signal between two frames: the frames before are whole, and the next is not begun.
    if (const int sig = interrupt_signal()) {
      std::fprintf(stderr, "%s: %s before frame %d; frames %d to %d were written\n", program,
                   sig == SIGTERM ? "terminated (SIGTERM)" : "interrupted (SIGINT)", f, range->first, f - 1);
      outcome.status = 128 + sig;
      break;
    }
    const OutputOptions frame_oo = frame_outputs(f);
    if (f != range->first) {
      prepared.pose_camera(frame_pose(prepared.camera_desc(), f, fps));
      if (write) prepare_outputs(frame_oo);
    }
    options.seed = frame_seed(c.seed, f);
    if (!c.quiet)
      std::fprintf(stderr, "%s: frame %d (t = %g s), %d of %d\n", program, f, frame_time(f, fps), f - range->first + 1,
                   range->count());
    outcome = render_and_write(c, prepared.world(), options, frame_oo, color, tiles.get(), program);
    if (outcome.status != 0 || f == range->last) break;
  }
  return outcome;
}

}  // namespace svbrdf
