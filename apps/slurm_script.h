#pragma once
// What the programs' --slurm submissions share (svbrdf-render's tiles, apps/render_slurm.h;
// svbrdf-lod-report's parts): the sbatch options both jobs of a submission take, the quoting of
// paths for the shell and for #SBATCH lines, and running or printing the submission script.
#include <CLI/CLI.hpp>

#include <filesystem>
#include <string>
#include <vector>

namespace svbrdf {

// Where a submission's jobs go: --slurm-partition, --slurm-account, --slurm-time, --slurm-option.
struct SlurmJobOptions {
  std::string partition, account, time;
  std::vector<std::string> sbatch_options;  // more #SBATCH lines, e.g. --mem=4G, for both jobs

  // `what`: the work one array task does ("each tile", "each part"), for --slurm-time's help.
  void add_to(CLI::App& app, const std::string& what);
};

// `text` as one word of a POSIX shell command.
std::string shell_quoted(const std::string& text);
// `text` as one argument of an #SBATCH line.
std::string directive_quoted(const std::string& text);
// A path as sbatch's --output takes it (% is the start of a job number there).
std::string output_pattern(const std::string& path);
// The #SBATCH lines both jobs share: where they run and log, and what the user passed on.
std::string common_directives(const SlurmJobOptions& s, const std::filesystem::path& folder);

// The command line's arguments (argv[1..]) without the options `drop` names, each with its value
// ("--out x", "--out=x", "-ox").
std::vector<std::string> without_options(const std::vector<std::string>& args,
                                         const std::vector<std::string>& drop);

// Refuses (bad input, naming `option`) a path that holds a line break: #SBATCH lines end at one.
void check_batch_path(const std::string& path, const std::string& option);

// This program's absolute path (/proc/self/exe), which the batch scripts run.
std::filesystem::path this_program();

// `print`: writes the script to standard output; `submit`: runs it through /bin/sh (its lines name
// the job ids). Throws svbrdf::Error when sbatch fails, naming `program` --slurm print to see why.
void run_submission(const std::string& mode, const std::string& script, const std::string& program);

}  // namespace svbrdf
