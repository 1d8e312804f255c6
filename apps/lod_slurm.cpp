#include "apps/lod_slurm.h"

#include <climits>
#include <system_error>

#include "base/cli_checks.h"
#include "base/error.h"
#include "base/output_location.h"

namespace svbrdf {

namespace fs = std::filesystem;

void LodSlurmOptions::add_to(CLI::App& app) {
  app.add_option(
         "--slurm", mode,
         "run the comparison on a Slurm cluster instead of here: print (the submission as a shell script) | "
         "submit (run sbatch: an array job of parts, then the report's assembly after it; prints the job "
         "ids)")
      ->check(CLI::IsMember({"print", "submit"}));
  app.add_option("--slurm-parts", parts, "with --slurm: the number of parts, one array task each (default 8)")
      ->check(cli::whole_in(1, INT_MAX));
  SlurmJobOptions::add_to(app, "each part and of the assembly");
}

std::string lod_slurm_submission(const LodSlurmOptions& s, const fs::path& program,
                                 const std::vector<std::string>& args, const fs::path& out,
                                 const fs::path& parts_dir, const std::string& ocio, const fs::path& folder) {
  const std::string n = std::to_string(s.parts), prog = shell_quoted(program.string());
  const std::string logs = output_pattern((parts_dir / "slurm-").string());
  // The array: task I renders part I of N (its shots k with k mod N = I) into the parts' folder.
  std::string array = "#!/bin/bash\n#SBATCH --job-name=svbrdf-lod-parts\n#SBATCH --array=0-" +
                      std::to_string(s.parts - 1) +
                      "\n#SBATCH --requeue\n#SBATCH --output=" + directive_quoted(logs + "%A_%a.log") + "\n" +
                      common_directives(s, folder) + "exec " + prog;
  for (const std::string& a : args) array += " " + shell_quoted(a);
  // Double quotes: the task's number is the shell's to expand, in the batch script.
  array += " --part \"$SLURM_ARRAY_TASK_ID/" + n + "\" --part-out " + shell_quoted(parts_dir.string()) + "\n";

  std::string assemble = "#!/bin/bash\n#SBATCH --job-name=svbrdf-lod-assemble\n#SBATCH --output=" +
                         directive_quoted(logs + "%j-assemble.log") + "\n" + common_directives(s, folder) +
                         "exec " + prog + " --assemble " + shell_quoted(parts_dir.string()) + " --out " +
                         shell_quoted(out.string());
  if (!ocio.empty()) assemble += " --ocio-config " + shell_quoted(ocio);
  assemble += "\n";

  // The batch scripts as here-documents with a quoted delimiter: sbatch gets them unexpanded.
  return "#!/bin/sh\n# svbrdf-lod-report --slurm: the LOD comparison into " + out.string() +
         " as a Slurm array job of " + n +
         " parts, then their assembly.\nset -e\n"
         "array=$(sbatch --parsable <<'SVBRDF_ARRAY'\n" +
         array +
         "SVBRDF_ARRAY\n)\narray=${array%%;*}\n"
         "assemble=$(sbatch --parsable --dependency=afterok:$array <<'SVBRDF_ASSEMBLE'\n" +
         assemble +
         "SVBRDF_ASSEMBLE\n)\n"
         "assemble=${assemble%%;*}\n"
         "echo \"parts: job $array (" +
         n + " array tasks); assemble: job $assemble, after them\"\n";
}

void run_lod_slurm(const LodSlurmOptions& s, const std::string& out, const std::string& parts_dir,
                   const std::string& ocio, int argc, char** argv) {
  const fs::path report = fs::absolute(out).lexically_normal();
  const fs::path parts =
      parts_dir.empty() ? fs::path(report.string() + ".parts") : fs::absolute(parts_dir).lexically_normal();
  for (const std::string& path : {report.string(), parts.string(), fs::current_path().string()})
    check_batch_path(path, "--slurm");
  check_output_folder(report / "img");
  check_output_folder(parts);
  // The tasks' logs go to the parts' folder, which sbatch does not make; `print` makes nothing.
  std::error_code ec;
  if (s.mode == "submit") fs::create_directories(parts, ec);
  if (ec) throw environment_error(parts.string(), "cannot create the parts' folder: " + ec.message());
  const std::vector<std::string> args =
      without_options(std::vector<std::string>(argv + 1, argv + argc),
                      {"--slurm", "--slurm-parts", "--slurm-partition", "--slurm-account", "--slurm-time",
                       "--slurm-option", "-o", "--out", "--part-out"});
  run_submission(s.mode,
                 lod_slurm_submission(s, this_program(), args, report, parts, ocio, fs::current_path()),
                 "svbrdf-lod-report");
}

}  // namespace svbrdf
