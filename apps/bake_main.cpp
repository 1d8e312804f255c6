// svbrdf-bake: bakes procedural materials into texture sets and builds, queries and compares MIP
// chains (../shared/spec/brdf-mip.md, "svbrdf-bake surface").
#include <CLI/CLI.hpp>

#include "apps/bake_commands.h"
#include "apps/run_program.h"
#include "base/interrupt.h"

int main(int argc, char** argv) {
  // A Ctrl-C or SIGTERM ends a bake at once with one line (exit 130 / 143), removing the temporary of
  // the file being written; the files already complete stay (base/interrupt.h).
  svbrdf::install_interrupt_handlers("svbrdf-bake");
  CLI::App app{"svbrdf-bake: bake material texture sets and BRDF-averaged MIP chains"};
  app.require_subcommand(1);
  svbrdf::add_material_command(app);
  svbrdf::add_mip_commands(app);
  svbrdf::add_scene_command(app);
  svbrdf::add_random_family_command(app);
  // The subcommands run as CLI11 callbacks, inside the parse.
  return svbrdf::run_program("svbrdf-bake", app, argc, argv, [] { return 0; });
}
