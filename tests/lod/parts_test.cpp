// The LOD comparison in parts (svbrdf-lod-report --part I/N --part-out DIR, then --assemble DIR): the
// assembled report is the single run's — every PNG the same bytes, results.json the same, index.html
// the same but for the time it took and the command it records — and the assembly refuses a part
// missing, cut short, copied over another or of another comparison, in one line naming the file.
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <regex>
#include <set>
#include <string>

#include "tests/common/run_command.h"
#include "tests/common/temp_dir.h"
#include "tests/common/test_paths.h"

namespace svbrdf {
namespace {

namespace fs = std::filesystem;
using testing::run_command;
using testing::slurp;
using testing::TempDir;

// One case, one light, one view, four distances (64× to 4096×), 4 samples per pixel: four shots.
const std::string kArgs =
    " --spp 4 --case printed-paper-text --light sun-0 --view head-on --min-distance 64 --max-distance 4096 "
    "-q";

std::string exe() { return SVBRDF_LOD_REPORT; }
std::string q(const fs::path& p) { return " '" + p.string() + "'"; }

std::set<std::string> names(const fs::path& dir) {
  std::set<std::string> out;
  for (const auto& e : fs::directory_iterator(dir)) out.insert(e.path().filename().string());
  return out;
}

// index.html without the two things that differ between runs of one comparison: the seconds it took
// and the command line.
std::string page(const fs::path& index) {
  std::string h = slurp(index);
  h = std::regex_replace(h, std::regex(R"(\. [0-9]+ s\.</p>)"), ". S s.</p>");
  return std::regex_replace(h, std::regex(R"(Made by <code>[^<]*</code>)"), "Made by <code>C</code>");
}

class LodParts : public ::testing::Test {
 protected:
  // Each process runs one test (ctest), so the renders are made when a test first needs them: the
  // refusals need the parts alone, the bad options neither.
  static void SetUpTestSuite() { dir_ = new TempDir; }
  static void render_parts() {
    if (fs::exists(dir() / "parts")) return;
    for (int i = 0; i < 3; ++i) {
      const auto part =
          run_command(exe() + kArgs + " --part " + std::to_string(i) + "/3 --part-out" + q(dir() / "parts"), dir());
      ASSERT_EQ(part.status, 0) << part.err;
      ASSERT_EQ(part.err, "");
    }
  }
  static void render_single() {
    if (fs::exists(dir() / "single")) return;
    const auto single = run_command(exe() + kArgs + " --out" + q(dir() / "single"), dir());
    ASSERT_EQ(single.status, 0) << single.err;
  }
  static void TearDownTestSuite() { delete dir_; }
  static fs::path dir() { return dir_->path(); }

  // A copy of the three parts to break.
  fs::path copy_parts(const std::string& name) {
    render_parts();
    const fs::path to = dir() / name;
    fs::remove_all(to);
    fs::copy(dir() / "parts", to, fs::copy_options::recursive);
    return to;
  }
  // The assembly of `parts` refused: exit 2, one line on stderr that contains `names`, no report.
  void refused(const fs::path& parts, const std::string& names_this) {
    const fs::path out = dir() / ("out-" + parts.filename().string());
    const auto r = run_command(exe() + " --assemble" + q(parts) + " -q -o" + q(out), dir());
    EXPECT_EQ(r.status, 2) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_NE(r.err.find(names_this), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(out));
  }

  static TempDir* dir_;
};
TempDir* LodParts::dir_ = nullptr;

TEST_F(LodParts, AssembledIsTheSingleRunsReport) {
  ASSERT_NO_FATAL_FAILURE(render_parts());
  ASSERT_NO_FATAL_FAILURE(render_single());
  const fs::path single = dir() / "single", assembled = dir() / "assembled";
  const auto r = run_command(exe() + " --assemble" + q(dir() / "parts") + " -q -o" + q(assembled), dir());
  ASSERT_EQ(r.status, 0) << r.err;
  // Four shots, each the ground truth and two images (render, error) per filter.
  const std::set<std::string> images = names(single / "img");
  ASSERT_GE(images.size(), 4u * 3u);
  EXPECT_EQ(names(assembled / "img"), images);
  for (const std::string& name : images)
    EXPECT_TRUE(slurp(single / "img" / name) == slurp(assembled / "img" / name)) << name << " differs";
  EXPECT_EQ(slurp(assembled / "results.json"), slurp(single / "results.json"));
  EXPECT_EQ(page(assembled / "index.html"), page(single / "index.html"));
  // Each part holds its own shots: k mod 3 of the four, so 2, 1 and 1 shots' truths.
  for (const auto& [part, count] : {std::pair{0, 2}, {1, 1}, {2, 1}}) {
    int truths = 0;
    for (const std::string& n : names(dir() / "parts"))
      if (n.rfind("lod-part-" + std::to_string(part) + "-of-3.shot-", 0) == 0 && n.ends_with(".truth.exr"))
        ++truths;
    EXPECT_EQ(truths, count) << "part " << part;
  }
}

TEST_F(LodParts, AMissingPartIsRefused) {
  const fs::path p = copy_parts("missing");
  fs::remove(p / "lod-part-1-of-3.json");
  refused(p, "lod-part-1-of-3.json");
}

TEST_F(LodParts, ACutShortPartIsRefused) {
  const fs::path p = copy_parts("cut");
  const std::string text = slurp(p / "lod-part-2-of-3.json");
  std::ofstream(p / "lod-part-2-of-3.json", std::ios::binary) << text.substr(0, text.size() / 2);
  refused(p, "lod-part-2-of-3.json");
  // An image of a part cut short.
  const fs::path q2 = copy_parts("cut-image");
  const fs::path truth = q2 / "lod-part-0-of-3.shot-3.truth.exr";
  const std::string bytes = slurp(truth);
  ASSERT_FALSE(bytes.empty());
  std::ofstream(truth, std::ios::binary) << bytes.substr(0, bytes.size() / 2);
  refused(q2, "lod-part-0-of-3.shot-3.truth.exr");
}

TEST_F(LodParts, APartCopiedOverAnotherIsRefused) {
  const fs::path p = copy_parts("copied");
  fs::copy_file(p / "lod-part-0-of-3.json", p / "lod-part-1-of-3.json", fs::copy_options::overwrite_existing);
  refused(p, "lod-part-1-of-3.json");
}

TEST_F(LodParts, APartOfAnotherComparisonIsRefused) {
  // Part 2 of the same shots at 8 samples per pixel, in place of the one at 4.
  const fs::path p = copy_parts("foreign");
  for (const std::string& n : names(p))
    if (n.rfind("lod-part-2-of-3", 0) == 0) fs::remove(p / n);
  const auto r = run_command(
      exe() + std::regex_replace(kArgs, std::regex("--spp 4"), "--spp 8") + " --part 2/3 --part-out" + q(p),
      dir());
  ASSERT_EQ(r.status, 0) << r.err;
  refused(p, "lod-part-2-of-3.json");
  // And a part of a run in two parts beside the three.
  const fs::path two = copy_parts("two-counts");
  const auto r2 = run_command(exe() + kArgs + " --part 1/2 --part-out" + q(two), dir());
  ASSERT_EQ(r2.status, 0) << r2.err;
  refused(two, "lod-part-");
}

// --slurm submit through a stand-in for sbatch that keeps each batch script and answers a job id;
// the scripts then run here as Slurm would run them (the array's script once per task number, in the
// submission's folder), into a report whose name has a space: the single run's report.
TEST_F(LodParts, TheSlurmSubmissionsScriptsMakeTheSingleRunsReport) {
  ASSERT_NO_FATAL_FAILURE(render_single());
  const fs::path farm = dir() / "farm", bin = dir() / "bin";
  fs::create_directories(farm);
  fs::create_directories(bin);
  std::ofstream(bin / "sbatch") << "#!/bin/sh\n"
                                   "n=$(ls \"$FAKE_SLURM\" | grep -c '^job-.*sh$')\n"
                                   "cat >\"$FAKE_SLURM/job-$n.sh\"\n"
                                   "echo \"$*\" >\"$FAKE_SLURM/job-$n.args\"\n"
                                   "echo \"$((100 + n));cluster\"\n";
  fs::permissions(bin / "sbatch", fs::perms::owner_all);
  const fs::path jobs = dir() / "jobs";
  fs::create_directories(jobs);
  const auto r =
      run_command("cd" + q(farm) + " && FAKE_SLURM=" + q(jobs).substr(1) + " PATH=" + q(bin).substr(1) +
                      ":\"$PATH\" " + exe() + kArgs + " -o 'lod report' --slurm-parts 3 --slurm submit",
                  dir());
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.out, "parts: job 100 (3 array tasks); assemble: job 101, after them\n");
  EXPECT_NE(slurp(jobs / "job-0.sh").find("#SBATCH --array=0-2\n"), std::string::npos);
  EXPECT_EQ(slurp(jobs / "job-1.args"), "--parsable --dependency=afterok:100\n");
  for (int i = 0; i < 3; ++i) {
    const auto task = run_command(
        "cd" + q(farm) + " && SLURM_ARRAY_TASK_ID=" + std::to_string(i) + " bash" + q(jobs / "job-0.sh"),
        dir());
    ASSERT_EQ(task.status, 0) << task.err;
  }
  const auto assemble = run_command("cd" + q(farm) + " && bash" + q(jobs / "job-1.sh"), dir());
  ASSERT_EQ(assemble.status, 0) << assemble.err;
  const fs::path single = dir() / "single", report = farm / "lod report";
  EXPECT_TRUE(fs::exists(farm / "lod report.parts" / "lod-part-2-of-3.json"));
  EXPECT_EQ(names(report / "img"), names(single / "img"));
  for (const std::string& name : names(single / "img"))
    EXPECT_TRUE(slurp(single / "img" / name) == slurp(report / "img" / name)) << name << " differs";
  EXPECT_EQ(slurp(report / "results.json"), slurp(single / "results.json"));
}

TEST_F(LodParts, BadPartOptionsAreRefused) {
  for (const std::string& args :
       {std::string(" --part 3/3 --part-out x"), std::string(" --part 1/0 --part-out x"),
        std::string(" --part 0/2"), std::string(" --part-out x"), std::string(" --part a/b --part-out x")}) {
    const auto r = run_command(exe() + kArgs + args, dir());
    EXPECT_EQ(r.status, 2) << args << ": " << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << args << ": " << r.err;
  }
  refused(dir() / "no-such-folder", "no-such-folder");
}

}  // namespace
}  // namespace svbrdf
