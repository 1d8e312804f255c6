// A warm load under `svbrdf-render --texture-cache` (TextureSet::find, render/texture_tiles.h): the
// images whose files an earlier render wrote are not decoded — the report line says so — and the
// render equals the cold one bit for bit, the images' floats and their 8-bit codes with tables read
// from the files' descriptions alike, and a MIP build with no record file reads its images from
// those files. An image file cut short, with
// garbled tables, or with no description is refused with one warning naming it, decoded and written
// again, and the render is still the cold one.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <regex>
#include <string>
#include <vector>

#include <OpenImageIO/imageio.h>

#include "tests/common/temp_dir.h"
#include "tests/render/quad_row.h"
#include "tests/render/render_child.h"

namespace svbrdf {
namespace {

namespace fs = std::filesystem;

using testing::Child;
using testing::expect_same_pixels;

using testing::baked_quad;

Child render(const fs::path& scene, const std::string& filter, const fs::path& cache, const fs::path& out,
             const fs::path& dir) {
  return testing::render_child({scene.string(), "--res", "40x32", "--spp", "4", "--filter", filter, "--float",
                                "--mip-cache", cache.string(), "--texture-cache", "10", "-o", out.string()},
                               dir);
}

// What the render's texture cache line says of the scene's images.
std::string image_counts(int decoded, int found) {
  return "(images: " + std::to_string(decoded) + " decoded, " + std::to_string(found) + " found there)";
}
// The images a cold render decoded (none found), from its line; −1 when it says otherwise.
int decoded_cold(const std::string& err) {
  std::smatch m;
  if (!std::regex_search(err, m, std::regex(R"(\(images: (\d+) decoded, 0 found there\))"))) return -1;
  return std::stoi(m[1].str());
}

int occurrences(const std::string& text, const std::string& what) {
  int n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

// The image files in `folder` (their description starts as render/image_file_description.h says),
// sorted.
std::vector<fs::path> image_files(const fs::path& folder) {
  std::vector<fs::path> out;
  for (const auto& e : fs::directory_iterator(folder)) {
    if (e.path().extension() != ".tx") continue;
    const auto in = OIIO::ImageInput::open(e.path().string());
    if (in && std::string(in->spec().get_string_attribute("ImageDescription")).rfind("svbrdf texture tiles", 0) == 0)
      out.push_back(e.path());
  }
  std::sort(out.begin(), out.end());
  return out;
}

std::string bytes_of(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}
void write_bytes(const fs::path& file, const std::string& bytes) {
  std::ofstream(file, std::ios::binary | std::ios::trunc) << bytes;
}

TEST(TextureCacheWarm, AWarmRenderDecodesNoImageAndEqualsTheColdRender) {
  const testing::TempDir dir;
  // sandstone: an 8-bit color image (codes, raw and linear tables), an 8-bit data image (codes, raw
  // table) and a 16-bit normal map (floats); metal-tray: 16-bit color images (floats and their
  // linearized copy's).
  for (const std::string preset : {"sandstone", "metal-tray"}) {
    SCOPED_TRACE(preset);
    const fs::path scene = baked_quad(dir.path(), preset), warm = dir.path() / (preset + "-warm"),
                   cold = dir.path() / (preset + "-cold");
    const auto out = [&](const std::string& name) { return dir.path() / (preset + "-" + name + ".exr"); };
    // level0: the lookups read the files' texels through the tables of their descriptions.
    const Child first = render(scene, "level0", warm, out("level0-cold"), dir.path());
    ASSERT_EQ(first.status, 0) << first.err;
    const int images = decoded_cold(first.err);
    ASSERT_GT(images, 0) << first.err;
    ASSERT_FALSE(image_files(warm).empty());
    const Child again = render(scene, "level0", warm, out("level0-warm"), dir.path());
    ASSERT_EQ(again.status, 0) << again.err;
    EXPECT_NE(again.err.find(image_counts(0, images)), std::string::npos) << again.err;
    EXPECT_EQ(occurrences(again.err, "warning:"), 0) << again.err;
    expect_same_pixels(out("level0-cold"), out("level0-warm"));
    if (preset != "sandstone") continue;
    // brdf with no record file for it: the MIP build reads its images back from the files found, and
    // the render equals one that decoded them.
    const Child reference = render(scene, "brdf", cold, out("brdf-cold"), dir.path());
    ASSERT_EQ(reference.status, 0) << reference.err;
    const Child built = render(scene, "brdf", warm, out("brdf-warm"), dir.path());
    ASSERT_EQ(built.status, 0) << built.err;
    EXPECT_NE(built.err.find(image_counts(0, images)), std::string::npos) << built.err;
    EXPECT_NE(built.err.find(", 1 built"), std::string::npos) << built.err;
    expect_same_pixels(out("brdf-cold"), out("brdf-warm"));
  }
}

// Writes `file` again as OpenImageIO reads it, without its description.
void strip_description(const fs::path& file) {
  auto in = OIIO::ImageInput::open(file.string());
  ASSERT_TRUE(in);
  OIIO::ImageSpec spec = in->spec();
  std::vector<unsigned char> texels(spec.image_bytes());
  ASSERT_TRUE(in->read_image(0, 0, 0, spec.nchannels, spec.format, texels.data()));
  in->close();
  spec.erase_attribute("ImageDescription");
  const fs::path tmp = file.string() + ".tmp.tif";
  auto out = OIIO::ImageOutput::create(tmp.string());
  ASSERT_TRUE(out);
  ASSERT_TRUE(out->open(tmp.string(), spec) && out->write_image(spec.format, texels.data()) && out->close());
  fs::rename(tmp, file);
}

// The three ways in one render, one file each: sandstone's files are its base colour's codes (with a
// linear table), its metal-roughness image's codes and its normal map's floats.
TEST(TextureCacheWarm, AFileCutShortOrBadlyDescribedIsWrittenAgainWithOneWarning) {
  const testing::TempDir dir;
  const fs::path scene = baked_quad(dir.path(), "sandstone"), cache = dir.path() / "cache";
  const Child first = render(scene, "level0", cache, dir.path() / "cold.exr", dir.path());
  ASSERT_EQ(first.status, 0) << first.err;
  ASSERT_EQ(decoded_cold(first.err), 3) << first.err;
  fs::path color, data, floats;
  for (const fs::path& f : image_files(cache)) {
    const std::string bytes = bytes_of(f);
    (bytes.find("\nform floats\n") != std::string::npos ? floats
     : bytes.find("\nlinear ") != std::string::npos     ? color
                                                        : data) = f;
  }
  ASSERT_FALSE(color.empty() || data.empty() || floats.empty());
  const std::uintmax_t sizes[3] = {fs::file_size(color), fs::file_size(data), fs::file_size(floats)};
  // The base colour's code table garbled, its length kept: every code would read as 1.
  {
    std::string garbled = bytes_of(color);
    const std::size_t at = garbled.find("\nraw ");
    ASSERT_NE(at, std::string::npos);
    for (std::size_t k = 0; k < 4 * 256; ++k) garbled.replace(at + 5 + 8 * k, 8, "3f800000");
    write_bytes(color, garbled);
  }
  strip_description(data);
  // Cut short by a byte: the header and every tile but the last are whole.
  fs::resize_file(floats, sizes[2] - 1);
  const Child c = render(scene, "level0", cache, dir.path() / "warm.exr", dir.path());
  ASSERT_EQ(c.status, 0) << c.err;
  EXPECT_EQ(occurrences(c.err, "warning:"), 3) << c.err;
  for (const fs::path& f : {color, data, floats})
    EXPECT_EQ(occurrences(c.err, "warning: the texture cache's file " + f.string() + ": "), 1) << f << "\n" << c.err;
  EXPECT_EQ(occurrences(c.err, "; it is written again"), 3) << c.err;
  EXPECT_NE(c.err.find(image_counts(3, 0)), std::string::npos) << c.err;
  expect_same_pixels(dir.path() / "cold.exr", dir.path() / "warm.exr");
  EXPECT_EQ(fs::file_size(color), sizes[0]);
  EXPECT_EQ(fs::file_size(data), sizes[1]);
  EXPECT_EQ(fs::file_size(floats), sizes[2]);
}

}  // namespace
}  // namespace svbrdf
