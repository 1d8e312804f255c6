// svbrdf-render: an Embree path tracer for textured glTF 2.0 scenes (issue 6). A thin main: parse
// the command line, call the library, map errors to exit codes (2 bad input, 1 internal failure,
// 130 interrupted after writing what had accumulated).
#include <CLI/CLI.hpp>

#include <atomic>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <string>
#include <unistd.h>

#include "base/cli_checks.h"
#include "base/error.h"
#include "base/message_line.h"
#include "render/gltf_loader.h"
#include "render/output.h"
#include "render/progress.h"
#include "render/render_setup.h"
#include "render/renderer.h"
#include "textures/color.h"

namespace {

std::atomic<bool> g_interrupted{false};  // set by SIGINT; the only state a signal handler may touch
extern "C" void on_sigint(int) { g_interrupted.store(true); }

namespace fs = std::filesystem;

// The showcase scene (issue 7) as the build places it; the first that exists wins.
fs::path find_showcase(const char* argv0) {
  std::error_code ec;
  fs::path exe = fs::canonical("/proc/self/exe", ec);
  if (ec) exe = fs::absolute(argv0);
  const fs::path dir = exe.parent_path();
  for (const fs::path& p : {dir / "scenes" / "showcase" / "showcase.gltf", dir / "scenes" / "showcase.gltf"})
    if (fs::exists(p, ec)) return p;
  // The program's name is the line's prefix already (main); the message names the file it looked for.
  throw svbrdf::input_error((dir / "scenes" / "showcase" / "showcase.gltf").string(),
                            "no scene given, and the showcase scene has not been built here; pass a glTF file, "
                            "or build it (make render)");
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"svbrdf-render: path-trace a textured glTF 2.0 scene"};
  std::string scene_file, out = "", png, res, camera, env, sun, filter = "brdf", light_sampling = "mis", ocio;
  int spp = 64, threads = 0, max_depth = 16;
  std::uint64_t seed = 0;
  double time_limit = 0.0;
  float exposure = 0.0f, footprint_scale = 0.0f;
  bool use_float = false, quiet = false, aovs = false;
  app.add_option("scene", scene_file, "glTF file (.gltf or .glb); none renders the project's showcase scene");
  app.add_option("-o,--out", out, "output OpenEXR file (linear radiance); default out/<scene>.exr");
  app.add_option("--png", png, "display PNG (default: beside the EXR, same stem)");
  app.add_option("--spp", spp, "samples per pixel")->check(svbrdf::cli::positive);
  app.add_option("--res", res, "resolution WxH (default: the camera's aspect at 360 rows, else 640x360)");
  app.add_option("--camera", camera, "camera index or name (default: the scene's first, else a framing camera)");
  app.add_option("--seed", seed, "random seed");
  app.add_option("--threads", threads, "worker threads (0: all cores)")->check(svbrdf::cli::non_negative);
  app.add_option("--max-depth", max_depth, "maximum number of scattering events")->check(svbrdf::cli::non_negative);
  app.add_option("--time-limit", time_limit, "stop after this many seconds and write what accumulated")
      ->check(svbrdf::cli::non_negative);
  app.add_option("--env", env, "environment: r,g,b radiance or an equirectangular HDR/EXR file "
                               "(default: white 1 when the scene has no lights, none when it has)");
  app.add_option("--sun", sun, "add a directional light: elevation,azimuth[,irradiance] (degrees, W/m^2)");
  const std::vector<std::string> filters = svbrdf::filter_names();
  std::string filter_help = "texture filter:";
  for (const std::string& f : filters) filter_help += (f == filters.front() ? " " : " | ") + f;
  filter_help += " (default brdf: the BRDF-averaged MIP; level0: the nearest texel, no MIP, the ground truth at many spp)";
  app.add_option("--filter", filter, filter_help)->check(CLI::IsMember(filters));
  app.add_option("--footprint-scale", footprint_scale,
                 "each camera sample's texture footprint as a fraction of its pixel's (default 1/sqrt(spp), its "
                 "share of the pixel; pbrt-v4 uses max(1/8, 1/sqrt(spp)); 1: the whole pixel)")
      ->check(svbrdf::cli::positive);
  app.add_option("--light-sampling", light_sampling, "environment sampling: mis | nee | bsdf")
      ->check(CLI::IsMember({"mis", "nee", "bsdf"}));
  app.add_option("--exposure", exposure, "exposure in stops for the PNG (the EXR is never scaled)");
  app.add_option("--ocio-config", ocio, "OpenColorIO config for texture decoding and the PNG (default: $OCIO, else the built-in one)");
  app.add_flag("--float", use_float, "write 32-bit float EXR (default half)");
  app.add_flag("--aov", aovs, "also write albedo, normal, depth and MIP-level EXRs beside the output");
  app.add_flag("-q,--quiet", quiet, "no progress output");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : 2;
  }

  try {
    const svbrdf::TextureFilter texture_filter = *svbrdf::parse_filter(filter);
    svbrdf::SceneSetup setup;
    setup.camera = camera;
    setup.env = env;
    setup.sun = sun;
    setup.filter = texture_filter;
    if (!res.empty()) {
      int w = 0, h = 0;
      char x = 0, extra = 0;
      if (std::sscanf(res.c_str(), "%d%c%d%c", &w, &x, &h, &extra) != 3 || (x != 'x' && x != 'X') || w < 1 || h < 1 ||
          w > 32768 || h > 32768)
        throw svbrdf::input_error("--res " + res, "expected WxH, e.g. 640x360");
      setup.width = w, setup.height = h;
    }
    const fs::path scene_path = scene_file.empty() ? find_showcase(argv[0]) : fs::path(scene_file);
    // The showcase is lit by a sun and its sky; glTF has no ratified way to carry an environment, so
    // the recipe bakes the sky beside the scene and the default render uses it unless --env says else.
    if (scene_file.empty() && env.empty() && fs::exists(scene_path.parent_path() / "sky.hdr"))
      setup.env = (scene_path.parent_path() / "sky.hdr").string();
    if (out.empty()) out = (fs::path("out") / scene_path.stem()).string() + ".exr";
    if (fs::path(out).extension() != ".exr") throw svbrdf::input_error("--out " + out, "the output must be an .exr file");

    const svbrdf::ColorConfig color =
        svbrdf::ColorConfig::resolve(ocio.empty() ? std::nullopt : std::optional<fs::path>(ocio));
    svbrdf::Scene scene = svbrdf::load_gltf(scene_path);
    for (const std::string& w : scene.warnings)
      std::fprintf(stderr, "svbrdf-render: warning: %s\n", svbrdf::message_line(w).c_str());
    const svbrdf::PreparedScene prepared(std::move(scene), setup, color);
    for (const std::string& w : prepared.mip_warnings(texture_filter))
      std::fprintf(stderr, "svbrdf-render: warning: %s\n", svbrdf::message_line(w).c_str());

    svbrdf::RenderOptions options;
    options.spp = spp;
    options.threads = threads;
    options.seed = seed;
    options.time_limit = time_limit;
    options.integrator.max_depth = max_depth;
    options.integrator.filter = texture_filter;
    options.integrator.footprints = aovs;  // the MIP-level AOV; the MIP filters compute their own
    options.integrator.footprint_scale = footprint_scale;  // 0: resolved to 1/√spp by render()
    options.aovs = aovs;
    options.integrator.light_sampling = light_sampling == "nee"    ? svbrdf::LightSampling::nee
                                        : light_sampling == "bsdf" ? svbrdf::LightSampling::bsdf
                                                                   : svbrdf::LightSampling::mis;
    options.cancel = &g_interrupted;
    svbrdf::ProgressPrinter printer(quiet);
    options.progress = [&](const svbrdf::ProgressInfo& p) { printer.update(p); };
    std::signal(SIGINT, on_sigint);
    svbrdf::RenderStats stats;
    const svbrdf::Film film = svbrdf::render(prepared.world(), options, &stats);
    std::signal(SIGINT, SIG_DFL);
    printer.finish({stats.samples, std::uint64_t(film.width) * film.height * std::uint64_t(spp), stats.rays, stats.seconds});

    svbrdf::OutputOptions oo;
    oo.exr = out;
    oo.png = png;
    oo.float32 = use_float;
    oo.exposure = exposure;
    oo.aovs = aovs;
    svbrdf::write_outputs(film, oo, color);
    if (!quiet) std::fprintf(stderr, "svbrdf-render: wrote %s\n", out.c_str());
    if (stats.interrupted) {
      std::fprintf(stderr, "svbrdf-render: interrupted; wrote the %llu samples that had accumulated\n",
                   static_cast<unsigned long long>(stats.samples));
      return 130;
    }
    return 0;
  } catch (const svbrdf::Error& e) {
    std::fprintf(stderr, "svbrdf-render: %s\n", svbrdf::message_line(e.what()).c_str());
    return e.exit_code();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "svbrdf-render: internal error: %s\n", svbrdf::message_line(e.what()).c_str());
    return 1;
  }
}
