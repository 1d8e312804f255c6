// svbrdf-brdf: a workbench for one BRDF model (../shared/spec/brdf-models.md, last section).
#include <CLI/CLI.hpp>
#include <cstdio>

#include "base/error.h"

int main(int argc, char** argv) {
  CLI::App app{"svbrdf-brdf: evaluate, sample and plot one BRDF model of CGPP chapter 27"};
  app.require_subcommand(1);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : 2;
  }
  return 0;
}
