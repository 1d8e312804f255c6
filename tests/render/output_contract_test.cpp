// svbrdf-render's outputs: a failed write is reported (exit 1) and replaces nothing, a path that
// cannot take the output is refused before the render starts, the EXR and the PNG are replaced
// together or not at all, and the temporaries of a killed run are removed by the next.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <filesystem>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "gltf_test_files.h"
#include "render_program.h"
#include "tests/common/read_only_folder.h"
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

// The disk fills while the later file of the set is written (the EXR with its AOV layers, after the
// PNG): the PNG is already whole in its temporary, yet neither replaces its previous file, and no
// temporary stays. Renaming each file as soon as it was written would leave a new PNG by an old EXR.
TEST(OutputContract, AFailedWriteOfALaterFileOfTheSetReplacesNone) {
  test::TempDir dir;
  const std::string q = scene(dir);
  const fs::path exr = dir.path() / "s.exr";
  const auto args = [&](const std::string& env) {
    return std::vector<std::string>{q, "-q", "--aov", "--env", env, "--res", "32x32", "--spp", "1", "-o", exr.string()};
  };
  const test::RenderRun first = test::render(args("1,1,1"), dir.path());
  ASSERT_TRUE(first.end.exited && first.end.code == 0) << first.err;
  const char* const names[] = {"s.exr", "s.png"};
  std::vector<std::string> previous;
  for (const char* name : names) previous.push_back(testing::slurp(dir.path() / name));
  // The limit in blocks of 512 bytes: the PNG fits, with 1 KiB to spare for the second image's, the
  // EXR not.
  const int blocks = static_cast<int>((fs::file_size(dir.path() / "s.png") + 511) / 512) + 2;
  ASSERT_GT(fs::file_size(exr), std::uintmax_t(blocks) * 512 + 256) << "the EXR must be the file of the set that does not fit";

  const test::RenderRun r = render_with_file_limit(blocks, args("0.5,0.5,0.5"), dir.path());  // another image
  ASSERT_TRUE(r.end.exited) << "killed by signal " << r.end.signal;
  EXPECT_EQ(r.end.code, 1) << r.err;
  EXPECT_EQ(test::line_count(r.err), 1) << r.err;
  EXPECT_NE(r.err.find("s.exr"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("File too large"), std::string::npos) << r.err;
  for (std::size_t i = 0; i < previous.size(); ++i)
    EXPECT_EQ(testing::slurp(dir.path() / names[i]), previous[i]) << names[i] << " was replaced by a failed run";
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
  const testing::ReadOnlyFolder read_only(dir.path());
  if (read_only.path().empty()) GTEST_SKIP() << "no folder here that refuses new files";
  const fs::path out = read_only.path() / "svbrdf-test.exr";
  const test::RenderRun r = test::render({q, "-q", "--res", "64x64", "--spp", "10000000", "-o", out.string()}, dir.path(), 30);
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
  const fs::path stale[] = {dir.path() / (".o.tmp" + dead + ".exr"), dir.path() / (".o.tmp" + dead + ".png")};
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
  EXPECT_TRUE(fs::exists(dir.path() / "o.exr"));
}

// SIGKILL while the outputs are written: nothing of the program runs (no handler, no clean-up), yet
// each output is its previous content or the new one whole, never a part, because only a finished
// temporary is renamed onto it; the temporaries left behind go with the next run of the same outputs.
// The kill races the write (a temporary seen may be renamed before the signal lands), so a run the
// kill came too late for is checked as a finished one and the kill tried again, up to kAttempts runs.
TEST(OutputContract, ASigkillWhileWritingLeavesEachFileWholeAndTheNextRunRemovesTheTemporaries) {
  test::TempDir dir;
  const std::string q = scene(dir);
  const fs::path exr = dir.path() / "k.exr";
  // A float EXR with its four AOV layers: the writes last long enough (tens of milliseconds) to be caught.
  const auto args = [&](const std::string& res) {
    return std::vector<std::string>{q, "--float", "--aov", "--res", res, "--spp", "1", "-o", exr.string()};
  };
  std::vector<std::string> quiet = args("512x512");
  quiet.push_back("-q");
  const test::RenderRun first = test::render(quiet, dir.path());
  ASSERT_TRUE(first.end.exited && first.end.code == 0) << first.err;

  constexpr int kAttempts = 6;
  bool left_temporaries = false;
  for (int attempt = 0; attempt < kAttempts && !left_temporaries; ++attempt) {
    std::vector<std::pair<fs::path, std::string>> previous;
    for (const auto& e : fs::directory_iterator(dir.path()))
      if (e.path().filename().string().rfind("k.", 0) == 0) previous.emplace_back(e.path(), testing::slurp(e.path()));
    ASSERT_EQ(previous.size(), 2u) << "the EXR and the PNG";

    std::vector<std::string> again = args("512x512");
    again.insert(again.begin(), test::kRenderProgram);
    // A different image each run, so a replaced file would show.
    again.insert(again.end(), {"--seed", std::to_string(7 + attempt)});
    const pid_t pid = testing::spawn_program(again, dir.path() / "stderr.txt");
    ASSERT_GT(pid, 0);
    // The render's summary line comes right before the outputs are written; then the first temporary
    // (the probe of the output folder before the render has the same name, hence the wait).
    ASSERT_TRUE(testing::wait_for_output(pid, dir.path() / "stderr.txt", " rays in ", 120)) << testing::slurp(dir.path() / "stderr.txt");
    bool caught = false;
    for (const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(60);
         !caught && std::chrono::steady_clock::now() < give_up;) {
      caught = !test::temp_files(dir.path()).empty();
      if (!caught) std::this_thread::sleep_for(std::chrono::microseconds(200));
      siginfo_t info{};
      if (!caught && (::waitid(P_PID, static_cast<id_t>(pid), &info, WEXITED | WNOHANG | WNOWAIT) != 0 || info.si_pid == pid)) break;
    }
    if (caught) ::kill(pid, SIGKILL);
    const testing::ProgramEnd end = testing::wait_program(pid, 60);
    ASSERT_FALSE(end.timed_out) << testing::slurp(dir.path() / "stderr.txt");
    if (end.signal != SIGKILL) {  // the write ended before a temporary was seen or before the kill landed
      ASSERT_TRUE(end.exited && end.code == 0) << testing::slurp(dir.path() / "stderr.txt");
    }
    left_temporaries = !test::temp_files(dir.path()).empty();
    if (left_temporaries) {
      EXPECT_EQ(end.signal, SIGKILL) << "only a killed run leaves its temporaries";
    }
    for (const auto& [path, bytes] : previous) {
      ASSERT_TRUE(fs::exists(path)) << path << " vanished";
      if (testing::slurp(path) == bytes) continue;
      EXPECT_EQ(read_image(path).width, 512) << path << " is neither the previous file nor a whole new one";
    }
  }
  ASSERT_TRUE(left_temporaries) << "in " << kAttempts << " runs no SIGKILL came while a temporary was written";

  std::vector<std::string> small = args("8x8");
  small.push_back("-q");
  const test::RenderRun next = test::render(small, dir.path());
  ASSERT_TRUE(next.end.exited && next.end.code == 0) << next.err;
  EXPECT_TRUE(test::temp_files(dir.path()).empty()) << test::temp_files(dir.path()).front();
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
