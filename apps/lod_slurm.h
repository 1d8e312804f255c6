#pragma once
// svbrdf-lod-report --slurm: the LOD comparison spread over a Slurm cluster. One sbatch array job of
// N tasks, task I running the comparison's part I of N (--part I/N, lod/parts.h) into the parts'
// folder, and an assembly job that depends on it (--dependency=afterok) writing the report
// (--assemble), the single run's. `print` prints the submission as a shell script, `submit` runs it
// and prints the job ids (apps/slurm_script.h; docs/farm.md).
#include <CLI/CLI.hpp>

#include <filesystem>
#include <string>
#include <vector>

#include "apps/slurm_script.h"

namespace svbrdf {

struct LodSlurmOptions : SlurmJobOptions {
  std::string mode;  // "print" or "submit"; empty: run here
  int parts = 8;

  void add_to(CLI::App& app);
};

// The submission script: `program` (absolute), `args` the command line without the --slurm options
// and -o/--out and --part-out, the report written to `out` and the parts to `parts_dir` (both
// absolute), run in `folder`; `ocio` the --ocio-config the assembly passes on (may be empty).
std::string lod_slurm_submission(const LodSlurmOptions& s, const std::filesystem::path& program,
                                 const std::vector<std::string>& args, const std::filesystem::path& out,
                                 const std::filesystem::path& parts_dir, const std::string& ocio,
                                 const std::filesystem::path& folder);

// Prints or submits the comparison of this command line (argv), the report into `out` and the parts
// into `parts_dir` (default: `out` with ".parts" added).
void run_lod_slurm(const LodSlurmOptions& s, const std::string& out, const std::string& parts_dir,
                   const std::string& ocio, int argc, char** argv);

}  // namespace svbrdf
