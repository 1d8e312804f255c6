// svbrdf-render: an Embree path tracer for textured glTF 2.0 scenes with BRDF-averaged MIP maps.
#include <CLI/CLI.hpp>
#include <cstdio>

int main(int argc, char** argv) {
  CLI::App app{"svbrdf-render: path-trace a textured glTF 2.0 scene"};
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : 2;
  }
  std::fprintf(stderr, "svbrdf-render: the path tracer has not landed yet (issue 6); nothing rendered\n");
  return 1;
}
