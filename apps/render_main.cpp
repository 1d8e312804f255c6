// svbrdf-render: an Embree path tracer for textured glTF 2.0 scenes. A thin main: parse the command
// line, call the library, map errors to exit codes (2 bad input, 1 internal or environment failure,
// 130 for SIGINT and 143 for SIGTERM, after writing what had accumulated when the render had begun).
#include <CLI/CLI.hpp>

#include <filesystem>
#include <string>
#include <vector>

#include "apps/baked_scenes.h"
#include "apps/render_command.h"
#include "apps/render_merge.h"
#include "apps/render_slurm.h"
#include "apps/run_program.h"
#include "base/error.h"
#include "base/interrupt.h"

namespace {

namespace fs = std::filesystem;

// The showcase scene as the build places it, or as it is installed; the first that exists wins.
fs::path find_showcase(const char* argv0) {
  for (const char* relative : {"showcase/showcase.gltf", "showcase.gltf"})
    if (const auto found = svbrdf::find_baked_scene(argv0, relative)) return *found;
  // The program's name is the line's prefix already (main); the message names the file it looked for.
  throw svbrdf::input_error((svbrdf::baked_scene_folders(argv0).front() / "showcase" / "showcase.gltf").string(),
                            "no scene given, and the showcase scene has not been built here; pass a glTF file, "
                            "or build it (make render)");
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
  svbrdf::RenderCommand command;
  command.add_options(app);
  bool merge = false;
  app.add_flag("--merge", merge,
               "assemble tiles (--tile, --crop) into the whole frame's EXR and PNG: svbrdf-render --merge -o OUT.exr "
               "TILE.exr... with the output options of the render (--png, --float, --exposure, --transparent, --ocio-config, "
               "--display, --view); with --frames A-B, each frame's tiles into that frame's "
               "output, every name (the tiles, -o, --png) given as the render's --out was, for --frames to name per frame");
  svbrdf::SlurmOptions slurm;
  slurm.add_to(app);
  return svbrdf::run_program("svbrdf-render", app, argc, argv, [&] {
    if (merge) {
      std::vector<fs::path> tiles;
      if (!command.scene_file.empty()) tiles.emplace_back(command.scene_file);
      tiles.insert(tiles.end(), command.more_inputs.begin(), command.more_inputs.end());
      svbrdf::run_merge(command, tiles, "svbrdf-render");
      return 0;
    }
    if (!slurm.mode.empty()) return svbrdf::run_slurm(slurm, command, argc, argv);
    const fs::path scene_path = command.scene_file.empty() ? find_showcase(argv[0]) : fs::path(command.scene_file);
    if (command.out.empty()) command.out = (fs::path("out") / scene_path.stem()).string() + ".exr";
    return svbrdf::run_render(command, scene_path, "svbrdf-render", svbrdf::interrupt_requested()).status;
  });
}
