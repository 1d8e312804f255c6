// svbrdf-render's outputs: a failed write is reported (exit 1) and replaces nothing, a path that
// cannot take the output is refused before the render starts, the EXR and the PNG are replaced
// together or not at all, and the temporaries of a killed run are removed by the next.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <string>
#include <thread>

#include "gltf_test_files.h"
#include "render_program.h"
#include "textures/image.h"

namespace svbrdf {
namespace {

namespace fs = std::filesystem;

std::string scene(const test::TempDir& dir) { return dir.write("q.gltf", test::GltfQuad().json()).string(); }

// A file-size limit (RLIMIT_FSIZE) stands in for a full disk: a write past it fails with EFBIG, as
// one on a full disk fails with ENOSPC, and neither needs privileges or a special file system.
// SIGXFSZ is ignored so that the write returns the error instead of killing the program.
test::RenderRun render_with_file_limit(int blocks_of_512, std::vector<std::string> args, const fs::path& dir) {
  args.insert(args.begin(), {"/bin/sh", "-c", "trap '' XFSZ; ulimit -f " + std::to_string(blocks_of_512) + "; exec \"$0\" \"$@\"",
                             test::kRenderProgram});
  return test::run_to_end(args, dir);
}

TEST(OutputContract, AFailedWriteIsReportedAndReplacesNothing) {
  test::TempDir dir;
  const std::string q = scene(dir);
  const fs::path exr = dir.path() / "a.exr", png = dir.path() / "a.png";
  // A noisy float image: its EXR is larger than the limit below.
  const std::vector<std::string> args = {q, "-q", "--float", "--res", "32x32", "--spp", "1", "-o", exr.string()};
  const test::RenderRun first = test::render(args, dir.path());
  ASSERT_TRUE(first.end.exited && first.end.code == 0) << first.err;
  ASSERT_GT(fs::file_size(exr), 1024u) << "the EXR must not fit under the limit";
  const std::string old_exr = testing::slurp(exr), old_png = testing::slurp(png);

  std::vector<std::string> again = args;
  again.insert(again.end(), {"--seed", "7"});  // a different image, so a replaced file would show
  const test::RenderRun r = render_with_file_limit(2, again, dir.path());
  ASSERT_TRUE(r.end.exited) << "killed by signal " << r.end.signal;
  EXPECT_EQ(r.end.code, 1) << "a failed write is the machine's failure, not bad input: " << r.err;
  EXPECT_EQ(test::line_count(r.err), 1) << r.err;
  EXPECT_TRUE(test::all_prefixed(r.err)) << r.err;
  EXPECT_NE(r.err.find("File too large"), std::string::npos) << r.err;
  EXPECT_EQ(testing::slurp(exr), old_exr) << "the EXR was replaced by a failed run";
  EXPECT_EQ(testing::slurp(png), old_png) << "the PNG was replaced by a failed run";
  EXPECT_TRUE(test::temp_files(dir.path()).empty());
}

TEST(OutputContract, AnOutputPathThatIsAFolderIsBadInput) {
  test::TempDir dir;
  const std::string q = scene(dir);
  fs::create_directories(dir.path() / "o.exr");
  fs::create_directories(dir.path() / "p.png");
  for (const auto& extra : {std::vector<std::string>{"-o", (dir.path() / "o.exr").string()},
                            std::vector<std::string>{"-o", (dir.path() / "p.exr").string(), "--png", (dir.path() / "p.png").string()}}) {
    std::vector<std::string> args = {q, "-q", "--res", "8x8", "--spp", "1"};
    args.insert(args.end(), extra.begin(), extra.end());
    const test::RenderRun r = test::render(args, dir.path());
    ASSERT_TRUE(r.end.exited);
    EXPECT_EQ(r.end.code, 2) << r.err;
    EXPECT_EQ(test::line_count(r.err), 1) << r.err;
    EXPECT_NE(r.err.find("is a folder"), std::string::npos) << r.err;
    EXPECT_EQ(r.err.find("Success"), std::string::npos) << r.err;
  }
  EXPECT_FALSE(fs::exists(dir.path() / "p.exr")) << "nothing written when one output cannot be";
  EXPECT_TRUE(test::temp_files(dir.path()).empty());
}

// Checked before the scene is read: a render of 10^7 samples per pixel ends at once.
TEST(OutputContract, AnUnwritableFolderIsRefusedBeforeRendering) {
  test::TempDir dir;
  const std::string q = scene(dir);
  fs::path out;
  if (::geteuid() == 0) {
    // Root writes through permission bits; sysfs takes no new files from anyone.
    if (!fs::is_directory("/sys/kernel")) GTEST_SKIP() << "no /sys to stand for a read-only folder";
    out = "/sys/kernel/svbrdf-test.exr";
  } else {
    fs::create_directories(dir.path() / "ro");
    fs::permissions(dir.path() / "ro", fs::perms::owner_read | fs::perms::owner_exec);
    out = dir.path() / "ro" / "o.exr";
  }
  const test::RenderRun r = test::render({q, "-q", "--res", "64x64", "--spp", "10000000", "-o", out.string()}, dir.path(), 30);
  if (::geteuid() != 0) fs::permissions(dir.path() / "ro", fs::perms::owner_all);
  ASSERT_TRUE(r.end.exited) << (r.end.timed_out ? "still rendering after 30 s" : "killed");
  EXPECT_EQ(r.end.code, 1) << r.err;
  EXPECT_EQ(test::line_count(r.err), 1) << r.err;
  EXPECT_NE(r.err.find(out.string()), std::string::npos) << r.err;
  EXPECT_LT(r.seconds, 10.0) << "the folder is checked before rendering, not after";
}

TEST(OutputContract, TheTemporariesOfAKilledRunAreRemoved) {
  test::TempDir dir;
  const std::string q = scene(dir);
  const std::string dead = std::to_string(testing::dead_pid()), alive = std::to_string(::getpid());
  const fs::path stale[] = {dir.path() / (".o.tmp" + dead + ".exr"), dir.path() / (".o.tmp" + dead + ".png"),
                            dir.path() / (".o.albedo.tmp" + dead + ".exr")};
  // Another run's temporary (its process lives) and a file of another name stay.
  const fs::path kept[] = {dir.path() / (".o.tmp" + alive + ".exr"), dir.path() / (".x.tmp" + dead + ".exr"),
                           dir.path() / (".o.tmp" + dead + ".exr.keep")};
  for (const fs::path& p : stale) dir.write(p.filename().string(), "partial");
  for (const fs::path& p : kept) dir.write(p.filename().string(), "partial");
  const test::RenderRun r =
      test::render({q, "-q", "--aov", "--res", "8x8", "--spp", "1", "-o", (dir.path() / "o.exr").string()}, dir.path());
  ASSERT_TRUE(r.end.exited && r.end.code == 0) << r.err;
  for (const fs::path& p : stale) EXPECT_FALSE(fs::exists(p)) << p;
  for (const fs::path& p : kept) EXPECT_TRUE(fs::exists(p)) << p;
  EXPECT_TRUE(fs::exists(dir.path() / "o.albedo.exr"));
}

// The PNG's path turns into a folder while the render runs: the EXR must not be written alone.
TEST(OutputContract, TheExrIsNotWrittenWithoutItsPng) {
  test::TempDir dir;
  const std::string q = scene(dir);
  const fs::path exr = dir.path() / "o.exr", png = dir.path() / "o.png";
  const pid_t pid = testing::spawn_program({test::kRenderProgram, q, "-q", "--res", "16x16", "--spp", "10000000", "--time-limit",
                                            "2", "-o", exr.string()},
                                           dir.path() / "stderr.txt");
  ASSERT_GT(pid, 0);
  std::this_thread::sleep_for(std::chrono::milliseconds(1000));
  fs::create_directories(png);
  const testing::ProgramEnd end = testing::wait_program(pid, 30);
  const std::string err = testing::slurp(dir.path() / "stderr.txt");
  ASSERT_TRUE(end.exited) << err;
  EXPECT_EQ(end.code, 2) << err;
  EXPECT_NE(err.find("is a folder"), std::string::npos) << err;
  EXPECT_FALSE(fs::exists(exr)) << "the EXR was written without its PNG";
  EXPECT_TRUE(test::temp_files(dir.path()).empty());
}

}  // namespace
}  // namespace svbrdf
