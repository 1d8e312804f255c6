#include "apps/render_slurm.h"

#include <climits>
#include <cstdio>
#include <system_error>

#include "apps/render_frames.h"
#include "base/cli_checks.h"
#include "base/error.h"

namespace svbrdf {

namespace fs = std::filesystem;

namespace {

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
  app.add_option("--slurm-tiles", tiles,
                 "with --slurm: the number of tiles of each frame, one array task each (default 4; with --frames 1: a "
                 "task renders a frame whole)")
      ->check(cli::whole_in(1, INT_MAX));
  SlurmJobOptions::add_to(app, "each task and of the merge");
}

std::string slurm_submission(const SlurmOptions& s, const RenderCommand& c, const fs::path& program,
                             const std::vector<std::string>& render_args, const fs::path& folder) {
  const fs::path out = fs::absolute(c.out).lexically_normal();
  const bool range = !c.frames.empty();
  const FrameRange frames_asked = range ? parse_frames(c.frames) : FrameRange{};
  const int tiles = s.tile_count(range);
  const std::string stem = (out.parent_path() / out.stem()).string(), n = std::to_string(tiles);
  const std::string prog = shell_quoted(program.string());
  const std::string png = c.png.empty() ? "" : fs::absolute(c.png).lexically_normal().string();
  const long long frames = frames_asked.count(), tasks = frames * tiles;

  // The array: task K renders tile K mod N of frame A + K div N (of the frame alone without --frames).
  std::string array = "#!/bin/bash\n#SBATCH --job-name=svbrdf-" + std::string(tiles > 1 ? "tiles" : "frames") +
                      "\n#SBATCH --array=0-" + std::to_string(tasks - 1) + "\n#SBATCH --requeue\n#SBATCH --output=" +
                      directive_quoted(output_pattern(stem + ".slurm-") + "%A_%a.log") + "\n" +
                      common_directives(s, folder);
  if (range) array += "frame=$((" + std::to_string(frames_asked.first) + " + SLURM_ARRAY_TASK_ID / " + n + "))\n";
  if (tiles > 1) array += "tile=$((SLURM_ARRAY_TASK_ID % " + n + "))\n";
  array += "exec " + prog;
  for (const std::string& a : render_args) array += " " + shell_quoted(a);
  // Double quotes: the frame and tile are the shell's to expand, in the batch script.
  array += " --quiet";
  if (range) array += " --frames \"$frame\"";
  if (tiles > 1)
    array += " --tile \"$tile/" + n + "\" --out " + shell_quoted(stem + ".tile-") + "\"$tile\"" + shell_quoted("-of-" + n + ".exr");
  else  // frames whole: each task writes its frame's output itself
    array += " --out " + shell_quoted(out.string()) + (png.empty() ? "" : " --png " + shell_quoted(png));
  array += "\n";

  const std::string head = "#!/bin/sh\n# svbrdf-render --slurm: " +
                           std::string(range ? "frames " + c.frames + " of " : "") + out.string() + " as a Slurm array job" +
                           (tiles > 1 ? " of tiles, then their merge" : "") + ".\nset -e\n";
  const std::string submit_array = "array=$(sbatch --parsable <<'SVBRDF_ARRAY'\n" + array + "SVBRDF_ARRAY\n)\n"
                                   "array=${array%%;*}\n";
  const std::string what = range ? std::to_string(frames) + " frames" + (tiles > 1 ? " x " + n + " tiles" : "")
                                 : n + " tiles";
  if (tiles == 1 && range)
    return head + submit_array + "echo \"frames: job $array (" + std::to_string(tasks) + " array tasks)\"\n";

  std::string merge = "#!/bin/bash\n#SBATCH --job-name=svbrdf-merge\n#SBATCH --output=" +
                      directive_quoted(output_pattern(stem + ".slurm-") + "%j-merge.log") + "\n" + common_directives(s, folder);
  merge += "exec " + prog + " --merge --quiet --out " + shell_quoted(out.string());
  if (range) merge += " --frames " + shell_quoted(c.frames);  // every frame's tiles, named as each task named them
  if (!png.empty()) merge += " --png " + shell_quoted(png);
  if (c.use_float) merge += " --float";
  if (c.transparent) merge += " --transparent";
  if (c.exposure != 0.0f) merge += " --exposure " + number_text(c.exposure);
  if (!c.ocio.empty()) merge += " --ocio-config " + shell_quoted(c.ocio);
  if (!c.display.empty()) merge += " --display " + shell_quoted(c.display);
  if (!c.view.empty()) merge += " --view " + shell_quoted(c.view);
  for (int i = 0; i < tiles; ++i) merge += " " + shell_quoted(stem + ".tile-" + std::to_string(i) + "-of-" + n + ".exr");
  merge += "\n";

  // The batch scripts as here-documents with a quoted delimiter: sbatch gets them unexpanded.
  return head + submit_array +
         "merge=$(sbatch --parsable --dependency=afterok:$array <<'SVBRDF_MERGE'\n" + merge + "SVBRDF_MERGE\n)\n"
         "merge=${merge%%;*}\n"
         "echo \"tiles: job $array (" + std::to_string(tasks) + " array tasks: " + what + "); merge: job $merge, after them\"\n";
}

int run_slurm(const SlurmOptions& s, const RenderCommand& c, int argc, char** argv) {
  if (!c.tile.empty() || !c.crop.empty())
    throw input_error("--slurm", "splits the frame into tiles itself (--slurm-tiles); leave out --tile and --crop");
  if (c.time_limit > 0.0)
    throw input_error("--slurm", "renders each tile whole, so that the merge is the single render; leave out --time-limit");
  if (!c.more_inputs.empty()) throw input_error(c.more_inputs.front(), "a second scene: --slurm renders one");
  if (c.out.empty()) throw input_error("--slurm", "needs -o/--out: the EXR the merge writes");
  // A batch script names these paths in #SBATCH lines, which end at a line break.
  for (const std::string& path : {c.out, c.png, fs::current_path().string()}) check_batch_path(path, "--slurm");
  if (!c.frames.empty()) {
    const long long tasks = (long long)(parse_frames(c.frames).count()) * s.tile_count(true);
    if (tasks > INT_MAX)
      throw input_error("--slurm-tiles " + std::to_string(s.tiles), "times the " + c.frames +
                                                                          " frames is more array tasks than Slurm numbers");
    // The frames' outputs, named as each task will name them, checked now (e.g. two runs of #).
    (void)frame_path(c.out, 0, "--out");
    if (!c.png.empty()) (void)frame_path(c.png, 0, "--png");
  }
  std::error_code ec;
  if (!c.scene_file.empty() && !fs::is_regular_file(c.scene_file, ec)) throw input_error(c.scene_file, "no such scene file");
  prepare_outputs(c.output_options());  // the folder exists (the logs and tiles go there) and takes the files
  if (c.fps != 0.0 && c.frames.empty()) throw input_error("--fps", "sets the rate of --frames; give --frames too");
  const std::vector<std::string> args = without_options(
      std::vector<std::string>(argv + 1, argv + argc),
      {"--slurm", "--slurm-tiles", "--slurm-partition", "--slurm-account", "--slurm-time", "--slurm-option", "-o", "--out",
       "--png", "--frames"});
  run_submission(s.mode, slurm_submission(s, c, this_program(), args, fs::current_path()), "svbrdf-render");
  return 0;
}

}  // namespace svbrdf
