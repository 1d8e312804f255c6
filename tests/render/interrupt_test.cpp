// svbrdf-render under --time-limit, SIGTERM and Ctrl-C: honoured within about a second at any stage
// of the run, with exit 0 / 143 / 130, one line for the signal, and a complete image or none. Each
// signal is sent once the program has said on stderr that it has reached the stage under test (its
// progress line), so the test holds on a loaded machine as on an idle one; the stages are made long
// enough (seconds) that the signal lands inside them. The bounds on time are generous (a loaded
// machine must pass): what they catch is a stop that waits for the stage to end — a whole tile's
// samples, minutes at 10^7 samples per pixel, or the rest of a build.
#include <gtest/gtest.h>
#include <signal.h>
#include <unistd.h>

#include <chrono>
#include <cstdint>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "gltf_test_files.h"
#include "render_program.h"
#include "textures/image.h"
#include "tests/common/test_paths.h"

namespace svbrdf {
namespace {

namespace fs = std::filesystem;

// A run signalled with `sig` once it printed `stage`.
struct Signalled {
  bool reached = false;       // the stage's line came before the program ended
  testing::ProgramEnd end;
  std::string err;            // all of stderr
  std::vector<std::string> after;  // the lines after the stage's line
  double seconds = 0;         // from the signal to the program's end
};

// `args[0]` is the program.
Signalled signal_at_stage(const std::vector<std::string>& args, const std::string& stage, int sig, const fs::path& dir) {
  const fs::path err = dir / "stderr.txt";
  Signalled s;
  const pid_t pid = testing::spawn_program(args, err);
  if (pid < 0) return s;
  // Two minutes: inputs are decoded under the sanitizers on a busy machine before the stage comes.
  // The stage's own line while it runs ("STAGE, 1 s"), not the one that says it is done.
  s.reached = testing::wait_for_output(pid, err, stage, 120, "done in");
  const auto sent = std::chrono::steady_clock::now();
  if (s.reached) ::kill(pid, sig);
  s.end = testing::wait_program(pid, 60);
  s.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - sent).count();
  s.err = testing::slurp(err);
  std::size_t at = s.err.find(stage);
  at = at == std::string::npos ? s.err.size() : s.err.find('\n', at);
  while (at != std::string::npos && at + 1 < s.err.size()) {
    const std::size_t nl = s.err.find('\n', at + 1);
    s.after.push_back(s.err.substr(at + 1, nl == std::string::npos ? std::string::npos : nl - at - 1));
    at = nl;
  }
  return s;
}

std::string signal_text(int sig) { return sig == SIGTERM ? "terminated (SIGTERM)" : "interrupted (SIGINT)"; }

// A PNG of 8-bit noise, `side` texels square: incompressible, so it takes its time to decode, and a
// normal map of it is rough everywhere, so its BRDF MIP build merges many lobes per texel.
fs::path write_noise_png(const test::TempDir& dir, const std::string& name, int side) {
  Image noise(side, side, 3);
  std::uint64_t state = 12345;
  for (float& v : noise.pixels) {
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    v = float(state >> 40) / float(1u << 24);
  }
  const fs::path p = dir.path() / name;
  write_image(p, noise, PixelFormat::uint8);
  return p;
}

// A quad whose material's normal map is 512² noise: its BRDF MIP build takes seconds.
std::string noise_normal_map_scene(const test::TempDir& dir) {
  write_noise_png(dir, "n.png", 512);
  test::GltfQuad quad;
  quad.texcoords = {0, 0, 1, 0, 1, 1, 0, 1};
  quad.materials = R"([{"normalTexture": {"index": 0}}])";
  quad.primitive_extra = R"(, "material": 0)";
  quad.top_extra = R"(, "images": [{"uri": "n.png"}], "textures": [{"source": 0}])";
  return dir.write("n.gltf", quad.json()).string();
}

std::vector<std::string> folder_listing(const fs::path& dir) {
  std::vector<std::string> names;
  if (!fs::exists(dir)) return names;
  for (const auto& e : fs::directory_iterator(dir)) names.push_back(e.path().filename().string());
  return names;
}

// The run ended by the signal before the render began: the one line that says so, nothing written.
void expect_ended_before_rendering(const Signalled& s, int sig, const fs::path& out) {
  ASSERT_TRUE(s.end.exited) << (s.end.timed_out ? "still running a minute after the signal"
                                                 : "killed by signal " + std::to_string(s.end.signal) + ", not ended by the program")
                            << ": " << s.err;
  EXPECT_EQ(s.end.code, 128 + sig) << s.err;
  EXPECT_LT(s.seconds, 5.0) << "the stage was finished before the program ended";
  EXPECT_TRUE(test::all_prefixed(s.err)) << s.err;
  ASSERT_EQ(s.after.size(), 1u) << "one line for the signal, and only that: " << s.err;
  EXPECT_NE(s.after[0].find(signal_text(sig)), std::string::npos) << s.err;
  EXPECT_NE(s.after[0].find("nothing written"), std::string::npos) << s.err;
  EXPECT_FALSE(fs::exists(out));
  EXPECT_FALSE(fs::exists(fs::path(out).replace_extension(".png")));
}

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

// The line that says how many samples per pixel were written: "the N samples per pixel" or "the N
// to M samples per pixel" (renderer.h: a render stopped within a pass). {N, M}, or {0, 0} when absent.
std::pair<long, long> written_samples(const std::string& line) {
  const std::size_t the = line.find("wrote the "), per = line.find(" samples per pixel");
  if (the == std::string::npos || per == std::string::npos || per < the) return {0, 0};
  const std::string counts = line.substr(the + 10, per - the - 10);
  const std::size_t to = counts.find(" to ");
  const long fewest = std::stol(counts.substr(0, to));
  return {fewest, to == std::string::npos ? fewest : std::stol(counts.substr(to + 4))};
}

// An image of the whole frame: every pixel has a sample. Every pixel of these scenes is lit (the quad
// under the white environment, or the environment itself), so a pixel without samples is black.
void expect_every_pixel_lit(const fs::path& exr) {
  const Image im = read_image(exr);
  int black = 0, first = -1;
  for (int y = 0; y < im.height; ++y)
    for (int x = 0; x < im.width; ++x)
      if (im.at(x, y, 0) + im.at(x, y, 1) + im.at(x, y, 2) <= 0.0f) {
        if (first < 0) first = y * im.width + x;
        ++black;
      }
  EXPECT_EQ(black, 0) << black << " of " << im.width * im.height << " pixels black, the first at (" << first % im.width << ", "
                      << first / im.width << ")";
}

// The time limit stops a render of many tiles in the first tiles' samples: what is written is the
// whole frame at the count every pixel reached, and one line says that the render stopped early and
// with how many samples per pixel, even under --quiet; the exit status is 0 (the limit was the user's).
TEST(Interrupt, ATimeLimitedRenderWritesTheWholeFrameAndSaysItStoppedEarly) {
  test::TempDir dir;
  const std::string q = dir.write("q.gltf", test::GltfQuad().json()).string();
  const fs::path out = dir.path() / "t.exr";
  // 16 tiles of 16×16 and far more samples than a second takes: tile by tile, two or so were done.
  const test::RenderRun r =
      test::render({q, "-q", "--res", "64x64", "--spp", "10000000", "--time-limit", "1", "-o", out.string()}, dir.path(), 60);
  ASSERT_TRUE(r.end.exited) << r.err;
  EXPECT_EQ(r.end.code, 0) << r.err;
  ASSERT_EQ(test::line_count(r.err), 1) << r.err;
  EXPECT_TRUE(test::all_prefixed(r.err)) << r.err;
  EXPECT_NE(r.err.find("stopped at the time limit (1 s); wrote the "), std::string::npos) << r.err;
  EXPECT_NE(r.err.find(", of 10000000"), std::string::npos) << r.err;
  const auto [fewest, most] = written_samples(r.err);
  EXPECT_GE(fewest, 1) << r.err;
  // The passes double the count: a pass cut short leaves at most twice what the previous one left.
  EXPECT_LE(fewest, most) << r.err;
  EXPECT_LE(most, 2 * fewest) << r.err;
  expect_every_pixel_lit(out);
  expect_every_pixel_lit(fs::path(out).replace_extension(".png"));
}

// A render that ends before its limit says nothing of it.
TEST(Interrupt, ARenderThatEndsWithinItsTimeLimitSaysNothingOfIt) {
  test::TempDir dir;
  const std::string q = dir.write("q.gltf", test::GltfQuad().json()).string();
  const test::RenderRun r = test::render(
      {q, "-q", "--res", "8x8", "--spp", "2", "--time-limit", "600", "-o", (dir.path() / "t.exr").string()}, dir.path());
  ASSERT_TRUE(r.end.exited) << r.err;
  EXPECT_EQ(r.end.code, 0) << r.err;
  EXPECT_EQ(r.err, "");
}

// While the scene is read: images are decoded one after another inside the image library, which
// polls nothing. A scene of many large images (hard links to one noise PNG, each an image of its own),
// each the base colour of a material of its own primitive, keeps the program in that stage for seconds:
// the reader decodes only the images a drawn material uses.
TEST(Interrupt, ASignalWhileTheSceneIsReadEndsTheRunAtOnceWithOneLine) {
  test::TempDir dir;
  const fs::path noise = write_noise_png(dir, "noise.png", 1024);
  constexpr int kImages = 64;
  std::string images, textures, materials, primitives;
  test::GltfQuad quad;
  quad.texcoords = {0, 0, 1, 0, 1, 1, 0, 1};
  const std::string one_primitive = R"({"attributes": {"POSITION": 0, "TEXCOORD_0": 2}, "indices": 1})";
  for (int i = 0; i < kImages; ++i) {
    // Appended piece by piece: GCC 12 warns falsely (-Wrestrict, PR 105651) on "n" + std::string.
    std::string name = "n";
    name += std::to_string(i);
    name += ".png";
    fs::create_hard_link(noise, dir.path() / name);
    const std::string comma = i ? ", " : "", index = std::to_string(i);
    images += comma + R"({"uri": ")" + name + R"("})";
    textures += comma + R"({"source": )" + index + "}";
    materials += comma + R"({"pbrMetallicRoughness": {"baseColorTexture": {"index": )" + index + "}}}";
    primitives += comma + R"({"attributes": {"POSITION": 0, "TEXCOORD_0": 2}, "indices": 1, "material": )" + index + "}";
  }
  quad.materials = "[" + materials + "]";
  quad.top_extra = R"(, "images": [)" + images + R"(], "textures": [)" + textures + "]";
  std::string json = quad.json();
  const std::size_t at = json.find(one_primitive);
  ASSERT_NE(at, std::string::npos) << "the quad's primitive is not written as this test expects: " << json;
  json.replace(at, one_primitive.size(), primitives);
  const std::string scene = dir.write("n.gltf", json).string();
  for (const int sig : {SIGINT, SIGTERM}) {
    SCOPED_TRACE(signal_text(sig));
    const fs::path out = dir.path() / "o.exr";
    const Signalled s = signal_at_stage({test::kRenderProgram, scene, "--res", "8x8", "--spp", "1", "-o", out.string()},
                                        "reading n.gltf and decoding its images", sig, dir.path());
    ASSERT_TRUE(s.reached) << "the reading stage never said it ran for a second: " << s.err;
    expect_ended_before_rendering(s, sig, out);
    EXPECT_EQ(s.err.find("done in"), std::string::npos) << "the scene was read before the signal came: " << s.err;
    EXPECT_TRUE(test::temp_files(dir.path()).empty());
  }
}

// While the BRDF MIP maps are built (here of a 512² noise normal map: seconds of work): the run ends
// at once, and the MIP cache is left without the entry, whole or partial, and without a temporary.
TEST(Interrupt, ASignalWhileTheMipMapsAreBuiltEndsTheRunAtOnceAndLeavesTheCacheWhole) {
  test::TempDir dir;
  const std::string scene = noise_normal_map_scene(dir);
  const fs::path cache = dir.path() / "cache";
  for (const int sig : {SIGINT, SIGTERM}) {
    SCOPED_TRACE(signal_text(sig));
    const fs::path out = dir.path() / "o.exr";
    const Signalled s = signal_at_stage(
        {test::kRenderProgram, scene, "--filter", "brdf", "--mip-cache", cache.string(), "--res", "8x8", "--spp", "1", "-o", out.string()},
        "building the brdf MIP maps", sig, dir.path());
    ASSERT_TRUE(s.reached) << "the build never said it ran for a second: " << s.err;
    expect_ended_before_rendering(s, sig, out);
    EXPECT_EQ(s.err.find("done in"), std::string::npos) << "the build ended before the signal came: " << s.err;
    EXPECT_TRUE(test::temp_files(dir.path()).empty());
    const std::vector<std::string> in_cache = folder_listing(cache);
    EXPECT_TRUE(in_cache.empty()) << in_cache.size() << " files in the MIP cache, the first " << in_cache.front();
  }
}

// svbrdf-bake filling the MIP cache (`mip SCENE.gltf`) is the same build: a signal ends it at once with
// one line, and the cache holds no part of the entry.
TEST(Interrupt, ASignalWhileSvbrdfBakeFillsTheMipCacheEndsItAtOnce) {
  test::TempDir dir;
  const std::string scene = noise_normal_map_scene(dir);
  const fs::path cache = dir.path() / "cache";
  for (const int sig : {SIGINT, SIGTERM}) {
    SCOPED_TRACE(signal_text(sig));
    const Signalled s =
        signal_at_stage({SVBRDF_BAKE, "mip", scene, "--mip-cache", cache.string()}, "building the brdf MIP maps", sig, dir.path());
    ASSERT_TRUE(s.reached) << "the build never said it ran for a second: " << s.err;
    ASSERT_TRUE(s.end.exited) << (s.end.timed_out ? "still running a minute after the signal" : "killed by the signal") << ": " << s.err;
    EXPECT_EQ(s.end.code, 128 + sig) << s.err;
    EXPECT_LT(s.seconds, 5.0) << "the build was finished before the program ended";
    ASSERT_EQ(s.after.size(), 1u) << "one line for the signal, and only that: " << s.err;
    EXPECT_EQ(s.after[0], "svbrdf-bake: " + signal_text(sig)) << s.err;
    const std::vector<std::string> in_cache = folder_listing(cache);
    EXPECT_TRUE(in_cache.empty()) << in_cache.size() << " files in the MIP cache, the first " << in_cache.front();
  }
}

// While rendering (SIGTERM is what `timeout`, systemd and batch schedulers send): the render stops,
// what accumulated is written as a whole EXR and PNG, and one line says so.
TEST(Interrupt, ASignalWhileRenderingWritesWhatAccumulated) {
  test::TempDir dir;
  const std::string q = dir.write("q.gltf", test::GltfQuad().json()).string();
  for (const int sig : {SIGINT, SIGTERM}) {
    SCOPED_TRACE(signal_text(sig));
    const fs::path out = dir.path() / (std::to_string(sig) + ".exr");
    // The renderer's first progress line ("0% after 00:00") comes once samples are being taken.
    const Signalled s =
        signal_at_stage({test::kRenderProgram, q, "--res", "32x32", "--spp", "10000000", "-o", out.string()}, "% after", sig, dir.path());
    ASSERT_TRUE(s.reached) << "the render never said it had begun: " << s.err;
    ASSERT_TRUE(s.end.exited) << (s.end.timed_out ? "still running a minute after the signal" : "killed by the signal") << ": "
                              << s.err;
    EXPECT_EQ(s.end.code, 128 + sig) << s.err;
    EXPECT_LT(s.seconds, 5.0);
    EXPECT_TRUE(test::all_prefixed(s.err)) << s.err;
    int mentions = 0;
    for (const std::string& line : s.after) mentions += line.find(signal_text(sig)) != std::string::npos;
    EXPECT_EQ(mentions, 1) << s.err;
    ASSERT_FALSE(s.after.empty());
    EXPECT_NE(s.after.back().find(signal_text(sig) + "; wrote the"), std::string::npos) << s.err;
    EXPECT_NE(s.after.back().find(" samples per pixel that had accumulated, of 10000000"), std::string::npos) << s.err;
    const auto [fewest, most] = written_samples(s.after.back());
    EXPECT_GE(fewest, 1) << s.err;
    EXPECT_LE(fewest, most) << s.err;
    EXPECT_LE(most, 2 * fewest) << s.err;
    ASSERT_TRUE(fs::exists(out)) << s.err;
    EXPECT_EQ(read_image(out).width, 32);
    EXPECT_EQ(read_image(fs::path(out).replace_extension(".png")).width, 32);
    // 4 tiles of 16×16 rendered by 2 threads: tile by tile, half the frame stayed black.
    expect_every_pixel_lit(out);
    EXPECT_TRUE(test::temp_files(dir.path()).empty());
  }
}

}  // namespace
}  // namespace svbrdf
