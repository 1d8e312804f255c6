// svbrdf-render under --time-limit, SIGTERM and Ctrl-C: honoured within about a second whatever the
// samples per pixel, with exit 0 / 143 / 130, one line per event, and a complete image or none. The
// bounds on time are generous (a loaded machine must pass): what they catch is a stop that waits for
// a whole tile's samples, minutes at 10^7 samples per pixel.
#include <gtest/gtest.h>
#include <signal.h>

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

TEST(Interrupt, TheTimeLimitStopsWithinTheSamplesOfAPixel) {
  test::TempDir dir;
  const std::string q = dir.write("q.gltf", test::GltfQuad().json()).string();
  const fs::path out = dir.path() / "t.exr";
  // One 16×16 tile of 10^7 samples per pixel: stopped only between tiles, this ran for minutes.
  const test::RenderRun r =
      test::render({q, "-q", "--res", "16x16", "--spp", "10000000", "--time-limit", "1", "-o", out.string()}, dir.path(), 30);
  ASSERT_FALSE(r.end.timed_out) << "still rendering 30 s into a 1 s limit";
  ASSERT_TRUE(r.end.exited);
  EXPECT_EQ(r.end.code, 0) << r.err;
  EXPECT_LT(r.seconds, 10.0);
  ASSERT_TRUE(fs::exists(out));
  EXPECT_EQ(read_image(out).width, 16);
}

// SIGTERM (what `timeout`, systemd and batch schedulers send) as Ctrl-C: the render stops, what
// accumulated is written, exit 143. Sent 1.5 s in, usually while rendering; if the machine is so slow
// that the scene is still loading, the run ends with nothing written — both keep the contract.
TEST(Interrupt, SigtermWritesWhatAccumulatedAndExits143) {
  test::TempDir dir;
  const std::string q = dir.write("q.gltf", test::GltfQuad().json()).string();
  const fs::path out = dir.path() / "s.exr", png = dir.path() / "s.png";
  const pid_t pid =
      testing::spawn_program({test::kRenderProgram, q, "-q", "--res", "32x32", "--spp", "10000000", "-o", out.string()},
                             dir.path() / "stderr.txt");
  ASSERT_GT(pid, 0);
  std::this_thread::sleep_for(std::chrono::milliseconds(1500));
  const auto sent = std::chrono::steady_clock::now();
  ::kill(pid, SIGTERM);
  const testing::ProgramEnd end = testing::wait_program(pid, 30);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - sent).count();
  const std::string err = testing::slurp(dir.path() / "stderr.txt");
  ASSERT_TRUE(end.exited) << (end.timed_out ? "still running 30 s after SIGTERM" : "killed by the signal") << ": " << err;
  EXPECT_EQ(end.code, 143) << err;
  EXPECT_LT(seconds, 10.0);
  EXPECT_TRUE(test::all_prefixed(err)) << err;
  EXPECT_NE(err.find("terminated (SIGTERM)"), std::string::npos) << err;
  if (fs::exists(out)) {
    EXPECT_EQ(read_image(out).width, 32);
    EXPECT_EQ(read_image(png).width, 32);
  } else {
    EXPECT_FALSE(fs::exists(png));
  }
  EXPECT_TRUE(test::temp_files(dir.path()).empty());
}

// Ctrl-C while the scene is being prepared (here the BRDF MIP chain of a 1024² noise normal map,
// seconds of work inside the library that polls nothing): one line and exit 130 at once, rather than
// dying silently by the signal.
TEST(Interrupt, CtrlCWhileTheSceneIsPreparedEndsAtOnceWithOneLine) {
  test::TempDir dir;
  Image noise(1024, 1024, 3);
  std::uint64_t state = 12345;
  for (float& v : noise.pixels) {
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    v = float(state >> 40) / float(1u << 24);
  }
  write_image(dir.path() / "n.png", noise, PixelFormat::uint8);
  test::GltfQuad quad;
  quad.texcoords = {0, 0, 1, 0, 1, 1, 0, 1};
  quad.materials = R"([{"normalTexture": {"index": 0}}])";
  quad.primitive_extra = R"(, "material": 0)";
  quad.top_extra = R"(, "images": [{"uri": "n.png"}], "textures": [{"source": 0}])";
  const std::string q = dir.write("n.gltf", quad.json()).string();
  const fs::path out = dir.path() / "n.exr";
  const pid_t pid = testing::spawn_program(
      {test::kRenderProgram, q, "-q", "--filter", "brdf", "--res", "8x8", "--spp", "1", "-o", out.string()}, dir.path() / "stderr.txt");
  ASSERT_GT(pid, 0);
  std::this_thread::sleep_for(std::chrono::milliseconds(1500));
  const auto sent = std::chrono::steady_clock::now();
  ::kill(pid, SIGINT);
  const testing::ProgramEnd end = testing::wait_program(pid, 30);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - sent).count();
  const std::string err = testing::slurp(dir.path() / "stderr.txt");
  ASSERT_TRUE(end.exited) << "killed by signal " << end.signal << ", not ended by the program: " << err;
  EXPECT_EQ(end.code, 130) << err;
  EXPECT_LT(seconds, 5.0);
  EXPECT_TRUE(test::all_prefixed(err)) << err;
  EXPECT_NE(err.find("interrupted (SIGINT)"), std::string::npos) << err;
  if (err.find("nothing written") != std::string::npos) {
    EXPECT_EQ(test::line_count(err), 1) << err;
    EXPECT_FALSE(fs::exists(out));
  }
  EXPECT_TRUE(test::temp_files(dir.path()).empty());
}

}  // namespace
}  // namespace svbrdf
