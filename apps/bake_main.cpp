// svbrdf-bake: bakes procedural materials into texture sets and builds, queries and compares MIP
// chains (../shared/spec/brdf-mip.md, "svbrdf-bake surface").
#include <CLI/CLI.hpp>
#include <cstdio>
#include <exception>

#include "base/cli_checks.h"
#include "base/error.h"
#include "base/interrupt.h"
#include "base/message_line.h"
#include "apps/bake_commands.h"

int main(int argc, char** argv) {
  // A Ctrl-C or SIGTERM ends a bake at once with one line (exit 130 / 143), removing the temporary of
  // the file being written; the files already complete stay (base/interrupt.h).
  svbrdf::install_interrupt_handlers("svbrdf-bake");
  CLI::App app{"svbrdf-bake: bake material texture sets and BRDF-averaged MIP chains"};
  app.require_subcommand(1);
  svbrdf::add_material_command(app);
  svbrdf::add_mip_commands(app);
  svbrdf::add_scene_command(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return svbrdf::cli::parse_failure(app, e, "svbrdf-bake");
  } catch (const svbrdf::Error& e) {
    std::fprintf(stderr, "svbrdf-bake: %s\n", svbrdf::message_line(e.what()).c_str());
    return e.exit_code();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "svbrdf-bake: internal error: %s\n", svbrdf::message_line(e.what()).c_str());
    return 1;
  }
  return 0;
}
