// svbrdf-bake: bakes procedural materials into texture sets and builds, queries and compares MIP
// chains (../shared/spec/brdf-mip.md, "svbrdf-bake surface").
#include <CLI/CLI.hpp>
#include <cstdio>
#include <exception>

#include "base/error.h"
#include "base/message_line.h"
#include "mip/bake_commands.h"

int main(int argc, char** argv) {
  CLI::App app{"svbrdf-bake: bake material texture sets and BRDF-averaged MIP chains"};
  app.require_subcommand(1);
  svbrdf::add_material_command(app);
  svbrdf::add_mip_commands(app);
  svbrdf::add_scene_command(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // --help and --version print through CLI11; a usage error is one line, as every bad input is.
    if (e.get_exit_code() == 0) return app.exit(e);
    std::fprintf(stderr, "svbrdf-bake: %s\n", svbrdf::message_line(e.what()).c_str());
    return 2;
  } catch (const svbrdf::Error& e) {
    std::fprintf(stderr, "svbrdf-bake: %s\n", svbrdf::message_line(e.what()).c_str());
    return e.exit_code();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "svbrdf-bake: internal error: %s\n", svbrdf::message_line(e.what()).c_str());
    return 1;
  }
  return 0;
}
