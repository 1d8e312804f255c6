#pragma once
// svbrdf-render --slurm: a render spread over a Slurm cluster. One sbatch array job renders the frame's
// tiles, one task a tile (--tile I/N, written beside the output), and a merge job that depends on
// it (--dependency=afterok) assembles them (--merge) into the output, the same bit for bit as one
// render on one machine. With --frames A-B the array has a task per frame and tile (frames × tiles),
// and the one merge job merges every frame; with one tile a frame (the default with --frames) each
// task renders its frame whole and writes its output, and there is no merge. `print` prints the
// submission as a shell script (the sbatch calls, each batch script inline); `submit` runs that same
// script and prints the job ids. Slurm itself retries a task whose node fails or which is preempted
// (--requeue). The tasks run in the folder the submission was made from, with the same program path:
// the cluster's nodes must share that file system (docs/farm.md).
#include <CLI/CLI.hpp>

#include <filesystem>
#include <string>
#include <vector>

#include "apps/render_command.h"
#include "apps/slurm_script.h"

namespace svbrdf {

struct SlurmOptions : SlurmJobOptions {
  std::string mode;  // "print" or "submit"; empty: render here
  int tiles = 0;  // 0: not given (tile_count)

  void add_to(CLI::App& app);
  // The tiles of each frame: --slurm-tiles, else 4 for one frame and 1 for --frames (a frame is a task).
  int tile_count(bool frames) const { return tiles > 0 ? tiles : frames ? 1 : 4; }
};

// The shell script that submits the render: `program` (an absolute path), `render_args` the
// command line's options and scene without the --slurm ones, -o/--out and --png (each task adds its
// --tile and its output), run in `folder`.
std::string slurm_submission(const SlurmOptions& slurm, const RenderCommand& command, const std::filesystem::path& program,
                             const std::vector<std::string>& render_args, const std::filesystem::path& folder);

// Prints the submission (print), or runs it through /bin/sh (submit), whose lines name the job ids.
// Returns the exit status; throws svbrdf::Error when sbatch fails.
int run_slurm(const SlurmOptions& slurm, const RenderCommand& command, int argc, char** argv);

}  // namespace svbrdf
