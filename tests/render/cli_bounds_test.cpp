// svbrdf-render's command line: a parse error is one line with the program's name and exit 2 (CLI11
// printed two without it), every number is checked against its range with a line naming the option,
// and --max-texels bounds the frame and every image read.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "gltf_test_files.h"
#include "render_program.h"
#include "textures/image.h"

namespace svbrdf {
namespace {

namespace fs = std::filesystem;

std::vector<std::string> split(const std::string& text) {
  std::vector<std::string> words;
  std::size_t at = 0;
  while (at < text.size()) {
    const std::size_t space = text.find(' ', at);
    words.push_back(text.substr(at, space == std::string::npos ? std::string::npos : space - at));
    at = space == std::string::npos ? text.size() : space + 1;
  }
  return words;
}

// Runs the quad scene with `extra` (words split at spaces) writing into `dir`.
test::RenderRun run_quad(const test::TempDir& dir, const std::string& extra) {
  std::vector<std::string> args = {dir.write("q.gltf", test::GltfQuad().json()).string(), "-q", "-o",
                                   (dir.path() / "o.exr").string()};
  for (const std::string& w : split(extra)) args.push_back(w);
  return test::render(args, dir.path());
}

void expect_refused(const test::RenderRun& r, const std::string& what, const std::string& names) {
  ASSERT_TRUE(r.end.exited) << what;
  EXPECT_EQ(r.end.code, 2) << what << ": " << r.err;
  EXPECT_EQ(test::line_count(r.err), 1) << what << ": " << r.err;
  EXPECT_TRUE(test::all_prefixed(r.err)) << what << ": " << r.err;
  EXPECT_NE(r.err.find(names), std::string::npos) << what << ": " << r.err;
  EXPECT_LT(r.err.size(), 240u) << what << ": " << r.err;
}

TEST(CliBounds, AParseErrorIsOneLineWithTheProgramsName) {
  test::TempDir dir;
  expect_refused(run_quad(dir, "--bogus"), "--bogus", "--bogus");
  expect_refused(run_quad(dir, "--spp"), "--spp without a value", "--spp");
  expect_refused(run_quad(dir, "--light-sampling sometimes"), "--light-sampling", "--light-sampling");
  expect_refused(test::render({"a.gltf", "b.gltf"}, dir.path()), "two scenes", "b.gltf");
  const test::RenderRun help = test::render({"--help"}, dir.path());
  ASSERT_TRUE(help.end.exited);
  EXPECT_EQ(help.end.code, 0);
  EXPECT_EQ(help.err, "");
}

// Each case starts the program (half a second of library loading), so one per kind of bound.
TEST(CliBounds, EveryNumberIsCheckedAgainstItsRange) {
  test::TempDir dir;
  for (const char* arg : {"--footprint-scale 1e30", "--spp 3000000000", "--spp 1.5", "--max-depth 1025", "--threads 99999999999",
                          "--time-limit inf", "--exposure nan", "--max-texels 0", "--seed -1"}) {
    const std::string option = std::string(arg).substr(0, std::string(arg).find(' '));
    expect_refused(run_quad(dir, arg), arg, option);
  }
  EXPECT_FALSE(fs::exists(dir.path() / "o.exr"));
}

// --res is held to the image writer's side and to --max-texels at the film's bytes per pixel, and
// parsed without overflow (sscanf's %d was undefined past 2^31).
TEST(CliBounds, TheResolutionIsCheckedBeforeTheSceneIsRead) {
  test::TempDir dir;
  for (const char* res : {"99999999999x1", "40000x1", "9000x9000", "1e3x10"})
    expect_refused(run_quad(dir, std::string("--res ") + res), res, std::string("--res ") + res);
  EXPECT_FALSE(fs::exists(dir.path() / "o.exr"));
}

TEST(CliBounds, TheBoundsThemselvesAreAccepted) {
  test::TempDir dir;
  const test::RenderRun r = run_quad(dir, "--res 8x8 --spp 1 --footprint-scale 64 --max-depth 1024 --exposure -64");
  ASSERT_TRUE(r.end.exited);
  EXPECT_EQ(r.end.code, 0) << r.err;
  // More threads than the machine runs: capped with a warning, not refused.
  const test::RenderRun t = run_quad(dir, "--res 8x8 --spp 1 --threads 100000");
  ASSERT_TRUE(t.end.exited);
  EXPECT_EQ(t.end.code, 0) << t.err;
  EXPECT_NE(t.err.find("svbrdf-render: warning: --threads 100000"), std::string::npos) << t.err;
}

TEST(CliBounds, MaxTexelsBoundsTheFrameAndTheTextures) {
  test::TempDir dir;
  expect_refused(run_quad(dir, "--res 8x8 --spp 1 --max-texels 63"), "a frame of 64 texels", "--max-texels");
  EXPECT_EQ(run_quad(dir, "--res 8x8 --spp 1 --max-texels 64").end.code, 0);
  // A 16×16 texture under --max-texels 100: refused as the glTF is read, before any render.
  write_image(dir.path() / "t.png", Image(16, 16, 3), PixelFormat::uint8);
  test::GltfQuad quad;
  quad.texcoords = {0, 0, 1, 0, 1, 1, 0, 1};
  quad.materials = R"([{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}])";
  quad.primitive_extra = R"(, "material": 0)";
  quad.top_extra = R"(, "images": [{"uri": "t.png"}], "textures": [{"source": 0}])";
  const std::string q = dir.write("t.gltf", quad.json()).string();
  const std::string out = (dir.path() / "t.exr").string();
  expect_refused(test::render({q, "-q", "--res", "8x8", "--spp", "1", "--max-texels", "100", "-o", out}, dir.path()),
                 "a 16x16 texture", "--max-texels");
  const test::RenderRun ok = test::render({q, "-q", "--res", "8x8", "--spp", "1", "--max-texels", "256", "-o", out}, dir.path());
  EXPECT_EQ(ok.end.code, 0) << ok.err;
}

}  // namespace
}  // namespace svbrdf
