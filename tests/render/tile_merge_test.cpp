// svbrdf-render --tile / --crop and --merge: a frame rendered in parts and merged is, bit for bit in
// every channel of the EXR and in the PNG, the frame rendered whole with the same seed; a part is
// placed in its frame by the EXR's data and display windows; a merge that cannot make the frame
// (a tile missing, corrupt, overlapping, of another frame) is refused in one line naming the tile.
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "gltf_test_files.h"
#include "render_program.h"
#include "textures/image.h"

namespace svbrdf {
namespace {

namespace fs = std::filesystem;

// A frame that sees the quad and the environment around it (alpha 0 and 1, depth 0 and not), lit by
// a sun too: noisy at 5 samples per pixel, so any sample drawn otherwise shows. 5 samples: passes of
// 1, 1, 2 and 1 (renderer.h).
std::vector<std::string> scene_args(const test::TempDir& dir) {
  const std::string q = (dir.path() / "q.gltf").string();
  if (!fs::exists(q)) std::ofstream(q) << test::GltfQuad().json();
  return {q, "-q", "--aov", "--res", "24x16", "--spp", "5", "--seed", "7", "--sun", "40,20,3"};
}

test::RenderRun render_with(const test::TempDir& dir, std::vector<std::string> extra) {
  std::vector<std::string> args = scene_args(dir);
  args.insert(args.end(), extra.begin(), extra.end());
  return test::render(args, dir.path());
}

test::RenderRun merge(const test::TempDir& dir, std::vector<std::string> args) {
  args.insert(args.begin(), {"--merge", "-q"});
  return test::render(args, dir.path());
}

// The two EXRs hold the same channels, stored alike, in the same windows, with the same bits.
void expect_same_exr(const fs::path& a, const fs::path& b) {
  const ExrImage x = read_exr(a), y = read_exr(b);
  ASSERT_EQ(x.names, y.names);
  EXPECT_EQ(x.formats, y.formats);
  EXPECT_EQ(x.window.x, y.window.x);
  EXPECT_EQ(x.window.y, y.window.y);
  EXPECT_EQ(x.window.frame_width, y.window.frame_width);
  EXPECT_EQ(x.window.frame_height, y.window.frame_height);
  ASSERT_EQ(x.image.width, y.image.width);
  ASSERT_EQ(x.image.height, y.image.height);
  ASSERT_EQ(x.image.pixels.size(), y.image.pixels.size());
  std::size_t differing = 0;
  for (std::size_t i = 0; i < x.image.pixels.size(); ++i)
    differing += std::memcmp(&x.image.pixels[i], &y.image.pixels[i], sizeof(float)) != 0;
  EXPECT_EQ(differing, 0u) << a << " and " << b << " differ in " << differing << " of " << x.image.pixels.size() << " values";
}

void expect_same_png(const fs::path& a, const fs::path& b) {
  const Image x = read_image(a), y = read_image(b);
  ASSERT_EQ(x.channels, y.channels);
  EXPECT_EQ(x.pixels, y.pixels) << a << " and " << b;
}

// Where a refused merge must leave things: exit 2, one line naming `named`, no output written.
void expect_refused(const test::RenderRun& r, const fs::path& out, const std::string& named) {
  EXPECT_TRUE(r.end.exited && r.end.code == 2) << r.err;
  EXPECT_EQ(test::line_count(r.err), 1) << r.err;
  EXPECT_TRUE(test::all_prefixed(r.err)) << r.err;
  EXPECT_NE(r.err.find(named), std::string::npos) << "not named: " << named << "\n" << r.err;
  EXPECT_FALSE(fs::exists(out));
  EXPECT_FALSE(fs::exists(fs::path(out).replace_extension(".png")));
}

TEST(TileMerge, FourTilesMergeIntoTheWholeRenderBitForBit) {
  test::TempDir dir;
  ASSERT_EQ(render_with(dir, {"-o", (dir.path() / "whole.exr").string()}).end.code, 0);
  std::vector<std::string> tiles;
  for (int i = 0; i < 4; ++i) {
    tiles.push_back((dir.path() / ("t" + std::to_string(i) + ".exr")).string());
    const test::RenderRun r = render_with(dir, {"--tile", std::to_string(i) + "/4", "-o", tiles.back()});
    ASSERT_TRUE(r.end.exited && r.end.code == 0) << r.err;
    EXPECT_FALSE(fs::exists(dir.path() / ("t" + std::to_string(i) + ".png"))) << "a tile is its EXR alone";
    // Band i of 4 of 16 rows: rows [4i, 4i + 4), placed in the 24x16 frame.
    const ExrImage t = read_exr(tiles.back());
    EXPECT_EQ(t.window.x, 0);
    EXPECT_EQ(t.window.y, 4 * i);
    EXPECT_EQ(t.image.width, 24);
    EXPECT_EQ(t.image.height, 4);
    EXPECT_EQ(t.window.frame_width, 24);
    EXPECT_EQ(t.window.frame_height, 16);
  }
  // Given in any order.
  const test::RenderRun m = merge(dir, {"-o", (dir.path() / "merged.exr").string(), tiles[2], tiles[0], tiles[3], tiles[1]});
  ASSERT_TRUE(m.end.exited && m.end.code == 0) << m.err;
  expect_same_exr(dir.path() / "whole.exr", dir.path() / "merged.exr");
  expect_same_png(dir.path() / "whole.png", dir.path() / "merged.png");
}

TEST(TileMerge, CropsInAGridMergeIntoTheWholeRenderWithItsOutputOptions) {
  test::TempDir dir;
  // Float EXR, a transparent background and an exposure: the PNG comes from the merge's floats.
  const std::vector<std::string> output = {"--float", "--transparent", "--exposure", "1.5"};
  std::vector<std::string> whole = output;
  whole.insert(whole.end(), {"-o", (dir.path() / "whole.exr").string()});
  ASSERT_EQ(render_with(dir, whole).end.code, 0);
  std::vector<std::string> args = output;
  args.insert(args.end(), {"-o", (dir.path() / "merged.exr").string()});
  int k = 0;
  for (const char* crop : {"0,0,7,5", "7,0,24,5", "0,5,13,16", "13,5,24,16"}) {
    args.push_back((dir.path() / ("c" + std::to_string(k++) + ".exr")).string());
    const test::RenderRun r = render_with(dir, {"--transparent", "--crop", crop, "-o", args.back()});
    ASSERT_TRUE(r.end.exited && r.end.code == 0) << r.err;
  }
  const ExrImage c1 = read_exr(dir.path() / "c1.exr");
  EXPECT_EQ(c1.window.x, 7);
  EXPECT_EQ(c1.window.y, 0);
  EXPECT_EQ(c1.image.width, 17);
  EXPECT_EQ(c1.image.height, 5);
  // A crop's pixel is the whole render's pixel at its place in the frame.
  const ExrImage w = read_exr(dir.path() / "whole.exr");
  for (int c = 0; c < w.image.channels; ++c)
    EXPECT_EQ(c1.image.at(3, 2, c), w.image.at(7 + 3, 2, c)) << w.names[std::size_t(c)];
  const test::RenderRun m = merge(dir, args);
  ASSERT_TRUE(m.end.exited && m.end.code == 0) << m.err;
  expect_same_exr(dir.path() / "whole.exr", dir.path() / "merged.exr");
  expect_same_png(dir.path() / "whole.png", dir.path() / "merged.png");
}

TEST(TileMerge, AMergeThatCannotMakeTheFrameIsRefusedNamingTheTile) {
  test::TempDir dir;
  std::vector<std::string> tiles;
  for (int i = 0; i < 2; ++i) {
    tiles.push_back((dir.path() / ("t" + std::to_string(i) + ".exr")).string());
    ASSERT_EQ(render_with(dir, {"--tile", std::to_string(i) + "/2", "-o", tiles.back()}).end.code, 0);
  }
  const fs::path out = dir.path() / "out.exr";
  // Missing.
  expect_refused(merge(dir, {"-o", out.string(), tiles[0], (dir.path() / "absent.exr").string()}), out, "absent.exr");
  // A gap: the second band's first pixel is in no tile.
  expect_refused(merge(dir, {"-o", out.string(), tiles[0]}), out, "pixel (0, 8)");
  // Overlapping: a crop across the two bands.
  const std::string over = (dir.path() / "over.exr").string();
  ASSERT_EQ(render_with(dir, {"--crop", "2,6,5,10", "-o", over}).end.code, 0);
  expect_refused(merge(dir, {"-o", out.string(), tiles[0], tiles[1], over}), out, "over.exr");
  // Corrupt: the file cut short.
  const fs::path cut = dir.path() / "cut.exr";
  fs::copy_file(tiles[1], cut);
  fs::resize_file(cut, fs::file_size(cut) / 2);
  expect_refused(merge(dir, {"-o", out.string(), tiles[0], cut.string()}), out, "cut.exr");
  // Of another frame, and of other channels.
  const std::string other = (dir.path() / "other.exr").string(), plain = (dir.path() / "plain.exr").string();
  std::vector<std::string> args = scene_args(dir);
  args[4] = "24x18";
  args.insert(args.end(), {"--tile", "1/2", "-o", other});
  ASSERT_EQ(test::render(args, dir.path()).end.code, 0);
  expect_refused(merge(dir, {"-o", out.string(), tiles[0], other}), out, "other.exr");
  args = scene_args(dir);
  args.erase(args.begin() + 2);  // no --aov
  args.insert(args.end(), {"--tile", "1/2", "-o", plain});
  ASSERT_EQ(test::render(args, dir.path()).end.code, 0);
  expect_refused(merge(dir, {"-o", out.string(), tiles[0], plain}), out, "plain.exr");
  // A whole render's half EXR is not a tile: its values are rounded.
  const std::string half = (dir.path() / "half.exr").string();
  ASSERT_EQ(render_with(dir, {"-o", half}).end.code, 0);
  expect_refused(merge(dir, {"-o", out.string(), half}), out, "half.exr");
}

TEST(TileMerge, ABadCropOrTileIsOneLine) {
  test::TempDir dir;
  const fs::path out = dir.path() / "x.exr";
  for (const std::vector<std::string>& bad :
       {std::vector<std::string>{"--crop", "1,2,3"}, {"--crop", "0,0,25,16"}, {"--crop", "4,0,4,16"}, {"--crop", "-1,0,3,3"},
        {"--tile", "4/4"}, {"--tile", "0/17"}, {"--tile", "1"}, {"--tile", "0/2", "--crop", "0,0,1,1"},
        {"--tile", "0/2", "--time-limit", "5"}, {"--tile", "0/2", "--png", (dir.path() / "x.png").string()}}) {
    std::vector<std::string> args = bad;
    args.insert(args.end(), {"-o", out.string()});
    expect_refused(render_with(dir, args), out, bad[0]);
  }
}

}  // namespace
}  // namespace svbrdf
