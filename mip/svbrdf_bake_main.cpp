// svbrdf-bake: bakes procedural materials into texture sets and builds, queries and compares MIP
// chains (../shared/spec/brdf-mip.md, "svbrdf-bake surface").
#include <CLI/CLI.hpp>

int main(int argc, char** argv) {
  CLI::App app{"svbrdf-bake: bake material texture sets and BRDF-averaged MIP chains"};
  app.require_subcommand(1);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : 2;
  }
  return 0;
}
