#pragma once
// The MIP cache's command-line options (render/mip_cache.h), the same in svbrdf-render and
// svbrdf-bake mip: --mip-cache DIR|off and --mip-cache-size MB.
#include <CLI/CLI.hpp>

#include <cmath>
#include <cstdio>
#include <memory>
#include <string>

#include "base/cli_checks.h"
#include "base/message_line.h"
#include "render/mip_cache.h"

namespace svbrdf {

struct MipCacheOptions {
  std::string folder;  // empty: the default folder; "off": none
  double megabytes = double(MipCache::kDefaultMegabytes);

  void add_to(CLI::App* app) {
    app->add_option("--mip-cache", folder,
                    "folder of finished brdf MIP builds that renders share, or 'off' (default: $SVBRDF_MIP_CACHE, else "
                    "$XDG_CACHE_HOME/svbrdf/mip, else ~/.cache/svbrdf/mip)");
    app->add_option("--mip-cache-size", megabytes,
                    "the most megabytes (10^6 bytes) the MIP cache keeps; the least recently used builds go first "
                    "(default " + std::to_string(MipCache::kDefaultMegabytes) + ")")
        ->check(cli::number_in(0.0, 1e9));
  }

  // The cache asked for, or null for none: 'off', or no folder can be named (one warning on stderr).
  std::unique_ptr<MipCache> open(const char* program) const {
    if (folder == "off") return nullptr;
    const std::optional<std::filesystem::path> dir = folder.empty() ? MipCache::default_folder() : std::filesystem::path(folder);
    if (!dir) {
      std::fprintf(stderr, "%s: warning: no MIP cache: neither $SVBRDF_MIP_CACHE, $XDG_CACHE_HOME nor $HOME names a folder "
                           "(--mip-cache DIR gives one)\n", program);
      return nullptr;
    }
    return std::make_unique<MipCache>(*dir, static_cast<std::uint64_t>(std::llround(megabytes * 1e6)));
  }
};

// Prints the cache's warnings, one line each.
inline void print_mip_cache_warnings(MipCache* cache, const char* program) {
  if (!cache) return;
  for (const std::string& w : cache->take_warnings())
    std::fprintf(stderr, "%s: warning: %s\n", program, message_line(w).c_str());
}

}  // namespace svbrdf
