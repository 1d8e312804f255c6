// `svbrdf-bake random-family [--seeds N] [--first-seed K] [--size S] [--json FILE] [--threads T]
// [--peak-weight W] [--lean-share S]`: the BRDF pyramid's error distribution over the random material
// family (textures/random_material.h), against the targets of docs/mip-algorithm.md §8, `brdf` beside
// `param` (apps/random_family_summary.h).
#include <CLI/CLI.hpp>

#include <atomic>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <tbb/global_control.h>
#include <tbb/parallel_for.h>

#include "apps/bake_commands.h"
#include "apps/random_family_summary.h"
#include "base/cli_checks.h"
#include "base/error.h"
#include "base/json.h"

namespace svbrdf {

namespace {

struct RandomFamilyOptions {
  int seeds = 100, size = 64, threads = 0;
  std::uint64_t first_seed = 1;
  std::string json;
  BrdfBuildOptions build;  // default but for the reduction constants under sweep
};

// The largest --size: a 4096² seed's exact reference is minutes per seed; larger is a typo.
constexpr int kMaxFamilySize = 4096;
constexpr int kMaxSeeds = 1'000'000;

void run_random_family(const RandomFamilyOptions& o) {
  if (o.first_seed > std::numeric_limits<std::uint64_t>::max() - std::uint64_t(o.seeds))
    throw input_error("--first-seed", "the seeds would pass 2^64 - 1");
  // A measurement run beside other work takes only the threads it is given.
  std::optional<tbb::global_control> limit;
  if (o.threads > 0) limit.emplace(tbb::global_control::max_allowed_parallelism, std::size_t(cli::capped_threads(o.threads, "svbrdf-bake")));
  std::vector<SeedFigures> figures(static_cast<std::size_t>(o.seeds));
  const auto start = std::chrono::steady_clock::now();
  std::atomic<int> done{0};
  // Seeds in parallel, and texels within each; the figures do not depend on the order.
  tbb::parallel_for(0, o.seeds, [&](int k) {
    figures[std::size_t(k)] = measure_random_seed(o.first_seed + std::uint64_t(k), o.size, o.build);
    const int n = ++done;
    const double t = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (t > 1.0) std::fprintf(stderr, "svbrdf-bake: random-family: %d of %d seeds (%.0f s)\n", n, o.seeds, t);
  });
  if (!o.json.empty()) write_json_file(o.json, family_json(figures, o.size));
  std::fputs(family_table(figures, o.size).c_str(), stdout);
}

}  // namespace

void add_random_family_command(CLI::App& app) {
  auto o = std::make_shared<RandomFamilyOptions>();
  CLI::App* cmd = app.add_subcommand(
      "random-family", "The BRDF MIP's error over seeds of the random material family, brdf against param, per level");
  cmd->add_option("--seeds", o->seeds, "how many seeds (default 100)")->check(cli::whole_in(1, kMaxSeeds));
  cmd->add_option("--first-seed", o->first_seed, "the first seed; seeds K, K+1, ... (default 1)")->check(cli::unsigned_whole);
  cmd->add_option("--size", o->size, "texels per side (default 64)")->check(cli::whole_in(2, kMaxFamilySize));
  cmd->add_option("--json", o->json, "also write every seed's figures and the distribution as JSON to FILE");
  // The reduction constants chosen on this family (docs/mip-algorithm.md §9), for sweeps.
  cmd->add_option("--peak-weight", o->build.reduction.peak_weight,
                  "weight of the merge cost's highlight term (default " + std::to_string(kPeakWeight) + ")")
      ->check(cli::number_in(0.0, 1.0));
  cmd->add_option("--lean-share", o->build.reduction.lean_peak_share_spread,
                  "share of the LEAN peak in a spread core's peak (default " + std::to_string(kLeanPeakShareSpread) + ")")
      ->check(cli::number_in(0.0, 1.0));
  cmd->add_option("--threads", o->threads, "worker threads (0: all cores; more than the machine runs at once are capped)")
      ->check(cli::whole_in(0, 4096));
  cmd->footer("Targets (docs/mip-algorithm.md, §8): e_log <= 0.01, e_mean <= 0.005, mean e_rel <= 0.02 outside the glint "
              "regime, directional albedo within 0.5 % at 0, 45 and 75 degrees.");
  cmd->callback([o] { run_random_family(*o); });
}

}  // namespace svbrdf
