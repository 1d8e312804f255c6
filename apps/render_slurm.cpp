#include "apps/render_slurm.h"

#include <climits>
#include <cstdio>
#include <system_error>

#include "base/cli_checks.h"
#include "base/error.h"

namespace svbrdf {

namespace fs = std::filesystem;

namespace {

// `text` as one word of a POSIX shell command: in single quotes, each ' as '\'' (POSIX.1-2017, Shell
// Command Language §2.2.2: nothing inside single quotes is special but the quote itself).
std::string quoted(const std::string& text) {
  std::string out = "'";
  for (const char ch : text) out += ch == '\'' ? std::string("'\\''") : std::string(1, ch);
  return out + "'";
}

// The #SBATCH lines both jobs share: where they run and log, and what the user passed on.
std::string common_directives(const SlurmOptions& s, const fs::path& folder) {
  std::string out = "#SBATCH --chdir=" + folder.string() + "\n";
  if (!s.partition.empty()) out += "#SBATCH --partition=" + s.partition + "\n";
  if (!s.account.empty()) out += "#SBATCH --account=" + s.account + "\n";
  if (!s.time.empty()) out += "#SBATCH --time=" + s.time + "\n";
  for (const std::string& o : s.sbatch_options) out += "#SBATCH " + o + "\n";
  return out;
}

std::string number_text(float v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.9g", double(v));  // 9 digits: the same float read back
  return buf;
}

}  // namespace

void SlurmOptions::add_to(CLI::App& app) {
  app.add_option("--slurm", mode,
                 "render on a Slurm cluster instead of here: print (the submission as a shell script) | submit (run "
                 "sbatch: an array job of tiles, then a merge job after it; prints the job ids)")
      ->check(CLI::IsMember({"print", "submit"}));
  app.add_option("--slurm-tiles", tiles, "with --slurm: the number of tiles, one array task each (default 4)")
      ->check(cli::whole_in(1, INT_MAX));
  app.add_option("--slurm-partition", partition, "with --slurm: sbatch's --partition for both jobs");
  app.add_option("--slurm-account", account, "with --slurm: sbatch's --account for both jobs");
  app.add_option("--slurm-time", time, "with --slurm: sbatch's --time limit of each task and of the merge");
  app.add_option("--slurm-option", sbatch_options,
                 "with --slurm: another sbatch option for both jobs, e.g. --slurm-option=--mem=4G (repeatable)");
}

std::vector<std::string> without_options(const std::vector<std::string>& args, const std::vector<std::string>& drop) {
  std::vector<std::string> out;
  for (std::size_t i = 0; i < args.size(); ++i) {
    bool dropped = false;
    for (const std::string& name : drop) {
      if (args[i] == name) {
        ++i;  // its value
      } else if (!(args[i].rfind(name + "=", 0) == 0 || (name.size() == 2 && args[i].rfind(name, 0) == 0))) {
        continue;
      }
      dropped = true;
      break;
    }
    if (!dropped) out.push_back(args[i]);
  }
  return out;
}

std::string slurm_submission(const SlurmOptions& s, const RenderCommand& c, const fs::path& program,
                             const std::vector<std::string>& render_args, const fs::path& folder) {
  const fs::path out = fs::absolute(c.out).lexically_normal();
  const std::string stem = (out.parent_path() / out.stem()).string(), n = std::to_string(s.tiles);
  const auto tile_file = [&](const std::string& index) { return stem + ".tile-" + index + "-of-" + n + ".exr"; };
  const std::string prog = quoted(program.string());

  std::string tiles = "#!/bin/bash\n#SBATCH --job-name=svbrdf-tiles\n#SBATCH --array=0-" + std::to_string(s.tiles - 1) +
                      "\n#SBATCH --requeue\n#SBATCH --output=" + stem + ".slurm-%A_%a.log\n" + common_directives(s, folder);
  tiles += "exec " + prog;
  for (const std::string& a : render_args) tiles += " " + quoted(a);
  // Double quotes: the task's index is the shell's to expand, in the batch script.
  tiles += " --quiet --tile \"$SLURM_ARRAY_TASK_ID/" + n + "\" --out " + quoted(stem + ".tile-") +
           "\"$SLURM_ARRAY_TASK_ID\"" + quoted("-of-" + n + ".exr") + "\n";

  std::string merge = "#!/bin/bash\n#SBATCH --job-name=svbrdf-merge\n#SBATCH --output=" + stem + ".slurm-%j-merge.log\n" +
                      common_directives(s, folder);
  merge += "exec " + prog + " --merge --quiet --out " + quoted(out.string());
  if (!c.png.empty()) merge += " --png " + quoted(fs::absolute(c.png).lexically_normal().string());
  if (c.use_float) merge += " --float";
  if (c.transparent) merge += " --transparent";
  if (c.exposure != 0.0f) merge += " --exposure " + number_text(c.exposure);
  if (!c.ocio.empty()) merge += " --ocio-config " + quoted(c.ocio);
  if (!c.display.empty()) merge += " --display " + quoted(c.display);
  if (!c.view.empty()) merge += " --view " + quoted(c.view);
  for (int i = 0; i < s.tiles; ++i) merge += " " + quoted(tile_file(std::to_string(i)));
  merge += "\n";

  // The batch scripts as here-documents with a quoted delimiter: sbatch gets them unexpanded.
  return "#!/bin/sh\n# svbrdf-render --slurm: the tiles of " + out.string() + " as a Slurm array job, then their merge.\n"
         "set -e\n"
         "tiles=$(sbatch --parsable <<'SVBRDF_TILES'\n" + tiles + "SVBRDF_TILES\n)\n"
         "tiles=${tiles%%;*}\n"
         "merge=$(sbatch --parsable --dependency=afterok:$tiles <<'SVBRDF_MERGE'\n" + merge + "SVBRDF_MERGE\n)\n"
         "merge=${merge%%;*}\n"
         "echo \"tiles: job $tiles (" + n + " array tasks); merge: job $merge, after them\"\n";
}

int run_slurm(const SlurmOptions& s, const RenderCommand& c, int argc, char** argv) {
  if (!c.tile.empty() || !c.crop.empty())
    throw input_error("--slurm", "splits the frame into tiles itself (--slurm-tiles); leave out --tile and --crop");
  if (c.time_limit > 0.0)
    throw input_error("--slurm", "renders each tile whole, so that the merge is the single render; leave out --time-limit");
  if (!c.more_inputs.empty()) throw input_error(c.more_inputs.front(), "a second scene: --slurm renders one");
  if (c.out.empty()) throw input_error("--slurm", "needs -o/--out: the EXR the merge writes");
  std::error_code ec;
  if (!c.scene_file.empty() && !fs::is_regular_file(c.scene_file, ec)) throw input_error(c.scene_file, "no such scene file");
  prepare_outputs(c.output_options());  // the folder exists (the logs and tiles go there) and takes the files
  const fs::path self = fs::read_symlink("/proc/self/exe", ec);
  if (ec) throw environment_error("/proc/self/exe", "cannot find this program's path: " + ec.message());
  const std::vector<std::string> args = without_options(
      std::vector<std::string>(argv + 1, argv + argc),
      {"--slurm", "--slurm-tiles", "--slurm-partition", "--slurm-account", "--slurm-time", "--slurm-option", "-o", "--out",
       "--png"});
  const std::string script = slurm_submission(s, c, self, args, fs::current_path());
  if (s.mode == "print") {
    std::fputs(script.c_str(), stdout);
    return 0;
  }
  std::fflush(stdout);
  FILE* sh = ::popen("/bin/sh -s", "w");
  if (!sh) throw environment_error("/bin/sh", "cannot start the submission");
  const bool written = std::fputs(script.c_str(), sh) >= 0;
  const int status = ::pclose(sh);
  if (!written || status != 0)
    throw environment_error("sbatch", "the submission failed (is Slurm's sbatch on PATH, and SLURM_CONF the cluster's?); "
                                      "svbrdf-render --slurm print shows what was run");
  return 0;
}

}  // namespace svbrdf
