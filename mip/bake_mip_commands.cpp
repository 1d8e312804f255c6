#include <CLI/CLI.hpp>

#include "mip/bake_commands.h"

namespace svbrdf {

// The MIP commands land with issue 5; until then the subcommands do not exist.
void add_mip_commands(CLI::App& /*app*/) {}

}  // namespace svbrdf
