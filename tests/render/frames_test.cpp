// svbrdf-render --frames on a small animated camera written here: a rig node, parent of the camera,
// moves by LINEAR translation from x = 0.5 at 0 s to x = 2.5 at 1 s above the unit quad. Frame 0 sees
// the quad at the frame's centre, frame 12 (t = 0.5 s at 24 fps: x = 1.5 by the closed form) sees past
// its edge there; a frame of a range is the frame rendered alone, bit for bit, and so are its tiles
// merged; the files are named by the rule of --help; and the reader refuses a broken animation in one
// line naming its JSON path, as the program refuses a bad range.
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "base/error.h"
#include "gltf/animation.h"
#include "gltf/scene_reader.h"
#include "gltf_test_files.h"
#include "render_program.h"
#include "textures/image.h"

namespace svbrdf {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

// The quad, a dark diffuse material, and the animated camera rig; `times` and `values` the sampler's.
json animated_quad(std::vector<float> times = {0.0f, 1.0f}, std::vector<float> values = {0.5f, 0.5f, 2, 2.5f, 0.5f, 2},
                   const std::string& interpolation = "LINEAR") {
  test::GltfQuad quad;
  quad.materials = R"([{"pbrMetallicRoughness": {"baseColorFactor": [0.2, 0.2, 0.2, 1], "metallicFactor": 0}}])";
  quad.primitive_extra = R"(, "material": 0)";
  json g = json::parse(quad.json());
  std::vector<unsigned char> bytes;
  test::append_bytes(bytes, times);
  test::append_bytes(bytes, values);
  g["buffers"].push_back({{"uri", "data:application/octet-stream;base64," + test::base64(bytes)},
                          {"byteLength", bytes.size()}});
  g["bufferViews"].push_back({{"buffer", 1}, {"byteOffset", 0}, {"byteLength", times.size() * 4}});
  g["bufferViews"].push_back({{"buffer", 1}, {"byteOffset", times.size() * 4}, {"byteLength", values.size() * 4}});
  const std::size_t views = g["bufferViews"].size(), accessors = g["accessors"].size();
  g["accessors"].push_back({{"bufferView", views - 2}, {"componentType", 5126}, {"count", times.size()}, {"type", "SCALAR"}});
  g["accessors"].push_back({{"bufferView", views - 1}, {"componentType", 5126}, {"count", values.size() / 3}, {"type", "VEC3"}});
  g["nodes"] = json::parse(R"([{"mesh": 0}, {"name": "rig", "children": [2], "translation": [0.5, 0.5, 2]}, {"camera": 0}])");
  g["scenes"][0]["nodes"] = {0, 1};
  g["cameras"] = json::parse(R"([{"type": "perspective", "perspective": {"yfov": 0.8, "znear": 0.01}}])");
  g["animations"] = {{{"channels", {{{"sampler", 0}, {"target", {{"node", 1}, {"path", "translation"}}}}}},
                      {"samplers", {{{"input", accessors}, {"output", accessors + 1}, {"interpolation", interpolation}}}}}};
  return g;
}

Image read(const fs::path& p) {
  EXPECT_TRUE(fs::exists(p)) << p;
  return fs::exists(p) ? read_image(p) : Image();
}

bool same_pixels(const Image& a, const Image& b) {
  return a.width == b.width && a.height == b.height && a.channels == b.channels && a.pixels == b.pixels;
}

const std::vector<std::string> kRender = {"--res", "16x12", "--spp", "3", "--seed", "7", "--transparent", "-q"};

std::vector<std::string> with(std::vector<std::string> args, const std::vector<std::string>& more) {
  args.insert(args.end(), more.begin(), more.end());
  return args;
}

TEST(Frames, AFrameOfARangeIsTheFrameRenderedAloneAndTheCameraMovesByItsAnimation) {
  test::TempDir dir;
  const std::string scene = dir.write("anim.gltf", animated_quad().dump()).string();
  const fs::path d = dir.path();
  // A range: one file per frame, the number before the extension.
  auto r = test::render(with({scene, "--frames", "11-12", "-o", (d / "seq.exr").string()}, kRender), d);
  ASSERT_EQ(r.end.code, 0) << r.err;
  // Alone, into a name with a # run: the number zero-padded to the run's width.
  r = test::render(with({scene, "--frames", "12", "-o", (d / "one.###.exr").string()}, kRender), d);
  ASSERT_EQ(r.end.code, 0) << r.err;
  r = test::render(with({scene, "--frames", "0", "-o", (d / "zero.exr").string()}, kRender), d);
  ASSERT_EQ(r.end.code, 0) << r.err;
  for (const char* f : {"seq.0011.exr", "seq.0011.png", "seq.0012.exr", "seq.0012.png", "one.012.exr", "zero.0000.exr"})
    EXPECT_TRUE(fs::exists(d / f)) << f;

  const Image twelve = read(d / "seq.0012.exr"), alone = read(d / "one.012.exr"), zero = read(d / "zero.0000.exr");
  EXPECT_TRUE(same_pixels(twelve, alone)) << "frame 12 of 11-12 differs from frame 12 rendered alone";
  EXPECT_FALSE(same_pixels(twelve, read(d / "seq.0011.exr")));
  // The alpha of the pixel right of the frame's centre (the quad covers it, or not, wholly): frame 0's
  // camera is above x = 0.5, the quad's middle; frame 12's, halfway through the LINEAR keys, above
  // x = 0.5 + (2.5 − 0.5)/2 = 1.5, half a quad past its edge.
  ASSERT_EQ(zero.channels, 4);
  EXPECT_EQ(zero.at(8, 6, 3), 1.0f);
  EXPECT_EQ(twelve.at(8, 6, 3), 0.0f);
}

TEST(Frames, AFramesTilesMergedAreTheFrame) {
  test::TempDir dir;
  const std::string scene = dir.write("anim.gltf", animated_quad().dump()).string();
  const fs::path d = dir.path();
  auto r = test::render(with({scene, "--frames", "5", "-o", (d / "whole.exr").string()}, kRender), d);
  ASSERT_EQ(r.end.code, 0) << r.err;
  for (const char* t : {"0/2", "1/2"}) {
    r = test::render(with({scene, "--frames", "5", "--tile", t, "-o", (d / ("t" + std::string(1, t[0]) + ".exr")).string()},
                          kRender),
                     d);
    ASSERT_EQ(r.end.code, 0) << r.err;
  }
  // The merge names each frame's tiles and output as the render did: t0.0005.exr, merged.0005.exr.
  EXPECT_TRUE(fs::exists(d / "t0.0005.exr"));
  r = test::render({"--merge", "--frames", "5", "--transparent", "-q", "-o", (d / "merged.exr").string(),
                    (d / "t0.exr").string(), (d / "t1.exr").string()},
                   d);
  ASSERT_EQ(r.end.code, 0) << r.err;
  EXPECT_TRUE(same_pixels(read(d / "merged.0005.exr"), read(d / "whole.0005.exr")));
}

// Exit 2, one line holding `expect`.
void expect_refused(const std::vector<std::string>& args, const std::string& expect) {
  test::TempDir dir;
  const test::RenderRun r = test::render(args, dir.path());
  EXPECT_EQ(r.end.code, 2) << r.err;
  EXPECT_EQ(test::line_count(r.err), 1) << r.err;
  EXPECT_NE(r.err.find(expect), std::string::npos) << "expected '" << expect << "' in: " << r.err;
}

TEST(Frames, BadRangesAndAStillCameraAreRefused) {
  test::TempDir dir;
  const std::string scene = dir.write("anim.gltf", animated_quad().dump()).string();
  const std::string out = (dir.path() / "o.exr").string();
  expect_refused({scene, "--frames", "5-3", "-o", out}, "--frames 5-3: the first frame comes after the last");
  expect_refused({scene, "--frames", "-2", "-o", out}, "--frames -2: frame numbers are 0 or more");
  expect_refused({scene, "--frames", "1-x", "-o", out}, "--frames 1-x: expected A-B");
  expect_refused({scene, "--fps", "30", "-o", out}, "--fps: sets the rate of --frames");
  expect_refused({scene, "--frames", "1", "-o", (dir.path() / "a#b#.exr").string()}, "has two runs of #");
  json still = animated_quad();
  still.erase("animations");
  const std::string still_scene = dir.write("still.gltf", still.dump()).string();
  expect_refused({still_scene, "--frames", "0-3", "-o", out}, "no animation of " + still_scene + " moves camera 'cameras[0]'");
  // A broken animation through the program: one line, exit 2, the JSON path.
  json broken = animated_quad();
  broken["animations"][0]["channels"][0]["sampler"] = 3;
  expect_refused({dir.write("broken.gltf", broken.dump()).string(), "--frames", "0", "-o", out},
                 "animations[0].channels[0].sampler: names sampler 3, but animations[0] has 1 samplers");
}

// What load_gltf says of `g` read for --frames (empty: nothing refused).
std::string refusal(const json& g) {
  test::TempDir dir;
  LoadOptions options;
  options.camera_animation = true;
  try {
    (void)load_gltf(dir.write("a.gltf", g.dump()), options);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(Frames, TheReaderRefusesABrokenAnimationNamingItsJsonPath) {
  EXPECT_EQ(refusal(animated_quad()), "");
  // Key times that do not increase; a time before 0.
  EXPECT_NE(refusal(animated_quad({0.0f, 0.0f})).find("animations[0].samplers[0].input: accessors[2] element 1 is 0 s"),
            std::string::npos);
  EXPECT_NE(refusal(animated_quad({-1.0f, 1.0f})).find("animations[0].samplers[0].input: accessors[2] begins at -1 s"),
            std::string::npos);
  // An input that is not float SCALAR.
  json g = animated_quad();
  g["accessors"][2]["type"] = "VEC2";
  g["accessors"][2]["count"] = 1;
  EXPECT_NE(refusal(g).find("animations[0].samplers[0].input: accessors[2] is VEC2"), std::string::npos) << refusal(g);
  // Three values for two keys; CUBICSPLINE with one element a key instead of three.
  EXPECT_NE(refusal(animated_quad({0.0f, 1.0f}, {0, 0, 2, 1, 0, 2, 2, 0, 2}))
                .find("animations[0].samplers[0].output: accessors[3] has 3 elements for 2 keys; LINEAR needs one per key"),
            std::string::npos);
  EXPECT_NE(refusal(animated_quad({0.0f, 1.0f}, {0, 0, 2, 1, 0, 2}, "CUBICSPLINE"))
                .find("animations[0].samplers[0].output: accessors[3] has 2 elements for 2 keys; CUBICSPLINE needs three"),
            std::string::npos);
  g = animated_quad();
  g["animations"][0]["samplers"][0]["interpolation"] = "SMOOTH";
  EXPECT_NE(refusal(g).find("animations[0].samplers[0].interpolation: is 'SMOOTH'"), std::string::npos);
  // Accessors that do not exist, or reach past their buffer: bounds checked, named.
  g = animated_quad();
  g["animations"][0]["samplers"][0]["input"] = 40;
  EXPECT_NE(refusal(g).find("animations[0].samplers[0].input: names accessors[40]"), std::string::npos) << refusal(g);
  g = animated_quad();
  g["accessors"][3]["count"] = 1000000;
  EXPECT_NE(refusal(g).find("animations[0].samplers[0].output"), std::string::npos) << refusal(g);
  // A target node given by a matrix; two channels of one animation on one property.
  g = animated_quad();
  g["nodes"][1].erase("translation");
  g["nodes"][1]["matrix"] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 2, 1};
  EXPECT_NE(refusal(g).find("animations[0].channels[0].target.node: names nodes[1], which has a matrix"), std::string::npos);
  g = animated_quad();
  g["animations"][0]["channels"].push_back(g["animations"][0]["channels"][0]);
  EXPECT_NE(refusal(g).find("animations[0].channels[1].target: animates the translation of nodes[1], as "
                            "animations[0].channels[0] does"),
            std::string::npos);
  // A channel tinygltf drops (no sampler) does not shift the names of the file's next channels.
  g = animated_quad();
  g["animations"][0]["channels"].insert(g["animations"][0]["channels"].begin(), {{"target", {{"node", 1}}}});
  g["animations"][0]["channels"][1]["sampler"] = 5;
  EXPECT_NE(refusal(g).find("animations[0].channels[1].sampler: names sampler 5"), std::string::npos) << refusal(g);
}

TEST(Frames, AStillRenderDoesNotReadAnimationsAndTheReaderPosesTheCameraByTheChain) {
  test::TempDir dir;
  json g = animated_quad();
  g["animations"][0]["samplers"][0]["interpolation"] = "SMOOTH";  // refused only when read
  EXPECT_NO_THROW((void)load_gltf(dir.write("a.gltf", g.dump())));
  LoadOptions options;
  options.camera_animation = true;
  const Scene scene = load_gltf(dir.write("b.gltf", animated_quad().dump()), options);
  ASSERT_EQ(scene.cameras.size(), 1u);
  ASSERT_TRUE(scene.cameras[0].motion);
  // The rig's LINEAR translation at 0.25 s: (0.5 + 0.25·2, 0.5, 2).
  const glm::dvec3 at(scene.cameras[0].motion->to_world(0.25) * glm::dvec4(0, 0, 0, 1));
  EXPECT_NEAR(at.x, 1.0, 1e-12);
  EXPECT_NEAR(at.y, 0.5, 1e-12);
  EXPECT_NEAR(at.z, 2.0, 1e-12);
  // Before the first key and after the last: the end values.
  EXPECT_NEAR((scene.cameras[0].motion->to_world(-1.0) * glm::dvec4(0, 0, 0, 1)).x, 0.5, 1e-12);
  EXPECT_NEAR((scene.cameras[0].motion->to_world(7.0) * glm::dvec4(0, 0, 0, 1)).x, 2.5, 1e-12);
}

}  // namespace
}  // namespace svbrdf
