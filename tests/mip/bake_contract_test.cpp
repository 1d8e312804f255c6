// svbrdf-bake's program contract beyond its commands' own bad input (cli_test.cpp): a failed write is
// reported with exit 1 and leaves no truncated file, an unwritable output folder is exit 1 before the
// work, a killed bake's temporaries are removed by the next, a parse error is one line with the program's
// name, every number is checked against its range, and --max-texels bounds the images read.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <utility>
#include <vector>

#include "tests/common/read_only_folder.h"
#include "tests/common/run_command.h"
#include "tests/common/spawn.h"
#include "textures/image.h"
#include "tests/common/test_paths.h"

namespace svbrdf {
namespace {

namespace fs = std::filesystem;

testing::CommandResult bake(const testing::TempDir& dir, const std::string& args) {
  return testing::run_command(std::string("'") + SVBRDF_BAKE + "' " + args, dir.path());
}

int lines(const std::string& s) { return static_cast<int>(std::count(s.begin(), s.end(), '\n')); }

std::string q(const fs::path& p) { return "'" + p.string() + "'"; }

// OpenImageIO's PNG writer does not report a failed write: a full disk left a truncated PNG under
// its real name and exit 0. A file-size limit stands in for the full disk (write(2) fails with EFBIG
// as it fails with ENOSPC); SIGXFSZ is ignored so the write returns the error.
TEST(BakeContract, AFailedPngWriteIsReportedAndLeavesNoTruncatedFile) {
  testing::TempDir dir;
  const fs::path out = dir / "m";
  const testing::CommandResult r = testing::run_command(
      std::string("trap '' XFSZ; ulimit -f 4; exec '") + SVBRDF_BAKE + "' material sandstone --size 64 --out " + q(out), dir.path());
  EXPECT_EQ(r.status, 1) << r.err;
  EXPECT_EQ(lines(r.err), 1) << r.err;
  EXPECT_EQ(r.err.rfind("svbrdf-bake: ", 0), 0u) << r.err;
  EXPECT_NE(r.err.find("File too large"), std::string::npos) << r.err;
  // The maps that fit are whole; the one that did not is absent, never cut short.
  int images = 0;
  if (fs::exists(out))
    for (const auto& e : fs::directory_iterator(out)) {
      const std::string name = e.path().filename().string();
      EXPECT_EQ(name.find(".tmp"), std::string::npos) << name;
      if (e.path().extension() != ".png") continue;
      ++images;
      EXPECT_NO_THROW(read_image(e.path())) << name << " is truncated";
    }
  EXPECT_LT(images, 3) << "the 20 KB normal map cannot fit under a 2 KB limit";
}

// A folder the machine does not let us write is its failure, not the user's (exit 2 is for bad
// input): one line and exit 1, said before the work rather than after it.
TEST(BakeContract, AnUnwritableOutputFolderIsExit1BeforeTheWork) {
  testing::TempDir dir;
  const testing::ReadOnlyFolder read_only(dir.path());
  if (read_only.path().empty()) GTEST_SKIP() << "no folder here that refuses new files";
  const fs::path& ro = read_only.path();
  for (const std::string& args : {"material sandstone --size 64 --out " + q(ro / "m"),
                                   "mip --base-color-factor 0.5,0.5,0.5 --out " + q(ro / "x.exr")}) {
    const testing::CommandResult r = bake(dir, args);
    EXPECT_EQ(r.status, 1) << args << ": " << r.err;
    EXPECT_EQ(lines(r.err), 1) << args << ": " << r.err;
    EXPECT_EQ(r.err.rfind("svbrdf-bake: " + ro.string(), 0), 0u) << args << ": " << r.err;
    EXPECT_EQ(r.out, "") << args << ": nothing was made";
  }
}

// The temporaries a killed bake left beside its outputs (its process gone) go with the next bake of
// the same outputs; another run's (its process alive) and other files stay.
TEST(BakeContract, TheTemporariesOfAKilledBakeAreRemoved) {
  testing::TempDir dir;
  const std::string dead = std::to_string(testing::dead_pid()), alive = std::to_string(::getpid());
  fs::create_directories(dir / "m");
  const fs::path stale[] = {dir / "m" / (".sandstone_normal.tmp" + dead + ".png"), dir / "m" / (".sandstone.tmp" + dead + ".gltf"),
                            dir / (".x.tmp" + dead + ".exr")};
  const fs::path kept[] = {dir / "m" / (".sandstone_normal.tmp" + alive + ".png"), dir / (".y.tmp" + dead + ".exr")};
  for (const fs::path& p : stale) std::ofstream(p) << "partial";
  for (const fs::path& p : kept) std::ofstream(p) << "partial";
  for (const std::string& args : {"material sandstone --size 64 --out " + q(dir / "m"),
                                  "mip --base-color-factor 0.5,0.5,0.5 --out " + q(dir / "x.exr")}) {
    const testing::CommandResult r = bake(dir, args);
    EXPECT_EQ(r.status, 0) << args << ": " << r.err;
  }
  for (const fs::path& p : stale) EXPECT_FALSE(fs::exists(p)) << p;
  for (const fs::path& p : kept) EXPECT_TRUE(fs::exists(p)) << p;
}

TEST(BakeContract, AParseErrorIsOneLineWithTheProgramsName) {
  testing::TempDir dir;
  for (const char* args : {"", "material", "mip --lobes", "material sandstone --out x --bogus"}) {
    const testing::CommandResult r = bake(dir, args);
    EXPECT_EQ(r.status, 2) << args << ": " << r.err;
    EXPECT_EQ(lines(r.err), 1) << args << ": " << r.err;
    EXPECT_EQ(r.err.rfind("svbrdf-bake: ", 0), 0u) << args << ": " << r.err;
  }
  const testing::CommandResult help = bake(dir, "--help");
  EXPECT_EQ(help.status, 0);
  EXPECT_EQ(help.err, "");
}

// Each case starts the program (half a second of library loading), so one per kind of bound.
TEST(BakeContract, EveryNumberIsCheckedAgainstItsRange) {
  testing::TempDir dir;
  const std::string m = " --out " + q(dir / "m"), mip = "mip --base-color-factor 1,1,1 --out " + q(dir / "x.exr");
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"material sandstone --size 99999999999" + m, "--size"},
      {"material sandstone --mm-per-texel 1e30" + m, "--mm-per-texel"},
      {"material sandstone --seed -1" + m, "--seed"},
      {"mip --base-color-factor 0.5,2,0.5 --out " + q(dir / "x.exr"), "--base-color-factor"},
      {mip + " --tolerance 1", "--tolerance"},
      {mip + " --normal-scale 1e30", "--normal-scale"},
      {mip + " --max-texels 0", "--max-texels"},
      {"eval " + q(dir / "f.exr") + " --level 0 --texel -1 0 --mode brdf", "--texel"},
      {"compare " + q(dir / "f.exr") + " --subset 1e9", "--subset"},
  };
  for (const auto& [args, option] : cases) {
    const testing::CommandResult r = bake(dir, args);
    EXPECT_EQ(r.status, 2) << args << ": " << r.err;
    EXPECT_EQ(lines(r.err), 1) << args << ": " << r.err;
    EXPECT_NE(r.err.find(option + ": must be a "), std::string::npos) << args << ": " << r.err;
  }
  EXPECT_FALSE(fs::exists(dir / "m"));
  EXPECT_FALSE(fs::exists(dir / "x.exr"));
}

TEST(BakeContract, MaxTexelsBoundsTheImagesRead) {
  testing::TempDir dir;
  write_image(dir / "bc.png", Image(16, 16, 3), PixelFormat::uint8);
  const std::string args = "mip --base-color " + q(dir / "bc.png") + " --out " + q(dir / "x.exr");
  const testing::CommandResult refused = bake(dir, args + " --max-texels 255");
  EXPECT_EQ(refused.status, 2) << refused.err;
  EXPECT_EQ(lines(refused.err), 1) << refused.err;
  EXPECT_NE(refused.err.find("--max-texels"), std::string::npos) << refused.err;
  EXPECT_FALSE(fs::exists(dir / "x.exr"));
  const testing::CommandResult ok = bake(dir, args + " --max-texels 256");
  EXPECT_EQ(ok.status, 0) << ok.err;
}

}  // namespace
}  // namespace svbrdf
