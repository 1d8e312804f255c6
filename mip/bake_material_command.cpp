#include <CLI/CLI.hpp>

#include "mip/bake_commands.h"

namespace svbrdf {

// The material presets land with issue 4; until then the subcommand does not exist.
void add_material_command(CLI::App& /*app*/) {}

}  // namespace svbrdf
