// The MIP cache (render/mip_cache.h) end to end: svbrdf-render and svbrdf-bake on a small textured
// glTF quad, each with its own cache folder inside the test's temporary folder. What a run did is read
// from its report ("MIP maps: R read from the MIP cache DIR, B built"), never from its timing; images
// are compared with a render that does not use the cache, texel for texel.
#include <gtest/gtest.h>

#include <sys/stat.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <regex>
#include <string>
#include <vector>

#include "base/sha256.h"
#include "mip/mip.h"
#include "render/mip_cache.h"
#include "scenes/texture_set.h"
#include "tests/common/run_command.h"
#include "tests/common/spawn.h"
#include "textures/image.h"
#include "tests/common/test_paths.h"

namespace svbrdf {
namespace {

namespace fs = std::filesystem;

std::string q(const fs::path& p) { return "'" + p.string() + "'"; }

// A metal tray quad, 64 texels a side, written as a glTF with PNG textures into `dir`.
TextureSetFiles tray(const fs::path& dir, std::uint64_t seed = 1) {
  MaterialRecipe r;
  r.preset = "metal-tray";
  r.size = 64;
  r.seed = seed;
  return bake_material(r, dir);
}

struct RenderRun {
  int status = -1;
  std::string err;
  int read = -1, built = -1;  // from the report; −1: none
  Image image;
};

// svbrdf-render SCENE with `cache` (a folder or "off"), a small frame; the EXR decoded.
RenderRun render(const testing::TempDir& dir, const fs::path& scene, const std::string& cache, const std::string& name) {
  const fs::path out = dir / (name + ".exr");
  const testing::CommandResult r = testing::run_command(
      q(fs::path(SVBRDF_BINARY_DIR) / "svbrdf-render") + " " + q(scene) + " --res 24x24 --spp 2 --mip-cache " + q(cache) +
          " -o " + q(out),
      dir.path());
  RenderRun run;
  run.status = r.status;
  run.err = r.err;
  std::smatch m;
  static const std::regex report("MIP maps: ([0-9]+) read from the MIP cache .*, ([0-9]+) built");
  if (std::regex_search(run.err, m, report)) run.read = std::stoi(m[1]), run.built = std::stoi(m[2]);
  if (run.status == 0) run.image = read_image(out);
  return run;
}

int count_lines(const std::string& text, const std::string& containing) {
  int n = 0;
  std::size_t at = 0;
  while ((at = text.find(containing, at)) != std::string::npos) ++n, at += containing.size();
  return n;
}

// The cache's entries (64 hexadecimal digits + ".exr"), and everything else in it.
std::vector<fs::path> entries(const fs::path& cache) {
  std::vector<fs::path> found;
  for (const auto& e : fs::directory_iterator(cache)) found.push_back(e.path());
  std::sort(found.begin(), found.end());
  return found;
}

// FIPS 180-4's examples (NIST's "SHA256.pdf" of the Cryptographic Standards and Guidelines examples)
// and the million 'a' of FIPS 180-2 Appendix B.3, whole and given in pieces.
TEST(MipCache, Sha256MatchesTheStandardsExamples) {
  EXPECT_EQ(to_hex(sha256("abc")), "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  EXPECT_EQ(to_hex(sha256("")), "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
  EXPECT_EQ(to_hex(sha256("abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq")),
            "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1");
  Sha256 pieces;
  const std::string a(1000, 'a');
  for (int i = 0; i < 1000; ++i) pieces.update(std::string_view(a).substr(0, 1 + i % 7)), pieces.update(std::string_view(a).substr(0, 999 - i % 7));
  EXPECT_EQ(to_hex(pieces.digest()), "cdc76e5c9914fb9281a1c7e284d73e67f1809a48a497200e046d39ccc7112cd0");
}

// A second render of the same scene reads its MIP maps from the cache and builds nothing; both images
// equal the render without the cache, bit for bit.
TEST(MipCache, ASecondRenderBuildsNothingAndCachedRendersAreBitIdentical) {
  testing::TempDir dir;
  const TextureSetFiles scene = tray(dir / "scene");
  const RenderRun uncached = render(dir, scene.gltf, "off", "uncached");
  ASSERT_EQ(uncached.status, 0) << uncached.err;
  EXPECT_EQ(uncached.read, -1) << uncached.err;  // no cache, no report
  const RenderRun first = render(dir, scene.gltf, (dir / "cache").string(), "first");
  ASSERT_EQ(first.status, 0) << first.err;
  EXPECT_EQ(first.read, 0) << first.err;
  EXPECT_EQ(first.built, 1) << first.err;
  const RenderRun second = render(dir, scene.gltf, (dir / "cache").string(), "second");
  ASSERT_EQ(second.status, 0) << second.err;
  EXPECT_EQ(second.read, 1) << second.err;
  EXPECT_EQ(second.built, 0) << second.err;
  EXPECT_EQ(first.image.pixels, uncached.image.pixels);
  EXPECT_EQ(second.image.pixels, uncached.image.pixels);
  EXPECT_EQ(entries(dir / "cache").size(), 1u);
}

// A texture whose bytes change has another key: the material is built again.
TEST(MipCache, AChangedTextureIsBuiltAgain) {
  testing::TempDir dir;
  const TextureSetFiles scene = tray(dir / "scene");
  ASSERT_EQ(render(dir, scene.gltf, (dir / "cache").string(), "a").built, 1);
  Image roughness = read_image(scene.metallic_roughness);
  roughness.at(3, 5, 1) = roughness.at(3, 5, 1) > 0.5f ? 0.0f : 1.0f;
  write_image(scene.metallic_roughness, roughness, PixelFormat::uint8);
  const RenderRun changed = render(dir, scene.gltf, (dir / "cache").string(), "b");
  ASSERT_EQ(changed.status, 0) << changed.err;
  EXPECT_EQ(changed.read, 0) << changed.err;
  EXPECT_EQ(changed.built, 1) << changed.err;
  EXPECT_EQ(entries(dir / "cache").size(), 2u);
}

// An entry that is truncated, has a flipped byte (in its texels or in a header value that still parses)
// or holds another key's build is said in one warning
// naming its file, built again and replaced; the image is the uncached one.
TEST(MipCache, ACorruptEntryIsRebuiltWithAWarning) {
  testing::TempDir dir;
  const TextureSetFiles scene = tray(dir / "scene");
  const TextureSetFiles other = tray(dir / "other", 2);
  const fs::path cache = dir / "cache";
  const RenderRun uncached = render(dir, scene.gltf, "off", "uncached");
  ASSERT_EQ(uncached.status, 0) << uncached.err;
  ASSERT_EQ(render(dir, other.gltf, cache.string(), "other").built, 1);
  const fs::path other_entry = entries(cache).at(0);
  ASSERT_EQ(render(dir, scene.gltf, cache.string(), "scene").built, 1);
  fs::path entry;
  for (const fs::path& e : entries(cache))
    if (e != other_entry) entry = e;
  ASSERT_FALSE(entry.empty());
  const std::string good = testing::slurp(entry);
  const auto corrupt = [&](const std::string& bytes) { std::ofstream(entry, std::ios::binary | std::ios::trunc) << bytes; };
  struct Case {
    const char* what;
    std::string bytes;
  };
  std::string flipped = good;
  flipped[flipped.size() / 2] = static_cast<char>(flipped[flipped.size() / 2] ^ 0x10);
  // A header value that parses either way: the radial grid's inner angle (OpenEXR attribute: name,
  // type, a 4-byte size, then the float's 4 bytes, little-endian).
  std::string header = good;
  const std::string attribute = std::string("svbrdf:radial_inner") + '\0' + "float" + '\0';
  const std::size_t at = header.find(attribute);
  ASSERT_NE(at, std::string::npos);
  header[at + attribute.size() + 4] = static_cast<char>(header[at + attribute.size() + 4] ^ 0x01);
  const Case cases[] = {{"truncated", good.substr(0, good.size() * 2 / 3)},
                        {"a flipped byte", flipped},
                        {"a changed header value", header},
                        {"another key's entry", testing::slurp(other_entry)}};
  for (const Case& c : cases) {
    SCOPED_TRACE(c.what);
    corrupt(c.bytes);
    const RenderRun run = render(dir, scene.gltf, cache.string(), "corrupt");
    ASSERT_EQ(run.status, 0) << run.err;
    EXPECT_EQ(count_lines(run.err, "warning: the MIP cache entry " + entry.string()), 1) << run.err;
    EXPECT_EQ(run.built, 1) << run.err;
    EXPECT_EQ(run.image.pixels, uncached.image.pixels);
    const RenderRun again = render(dir, scene.gltf, cache.string(), "again");  // the entry was replaced
    EXPECT_EQ(again.read, 1) << again.err;
    EXPECT_EQ(count_lines(again.err, "warning"), 0) << again.err;
  }
}

// Two renders started together into one empty cache both succeed with the same image, and leave one
// whole entry and no temporary.
TEST(MipCache, TwoConcurrentRendersIntoAnEmptyCacheAgree) {
  testing::TempDir dir;
  const TextureSetFiles scene = tray(dir / "scene");
  const fs::path cache = dir / "cache";
  const RenderRun uncached = render(dir, scene.gltf, "off", "uncached");
  ASSERT_EQ(uncached.status, 0) << uncached.err;
  pid_t pids[2];
  for (int k = 0; k < 2; ++k)
    pids[k] = testing::spawn_program({(fs::path(SVBRDF_BINARY_DIR) / "svbrdf-render").string(), scene.gltf.string(), "--res",
                                      "24x24", "--spp", "2", "--mip-cache", cache.string(), "-o",
                                      (dir / ("both" + std::to_string(k) + ".exr")).string()},
                                     dir / ("err" + std::to_string(k) + ".txt"));
  for (int k = 0; k < 2; ++k) {
    ASSERT_GT(pids[k], 0);
    const testing::ProgramEnd end = testing::wait_program(pids[k], 300);
    EXPECT_TRUE(end.exited && end.code == 0) << testing::slurp(dir / ("err" + std::to_string(k) + ".txt"));
    EXPECT_EQ(read_image(dir / ("both" + std::to_string(k) + ".exr")).pixels, uncached.image.pixels);
  }
  const std::vector<fs::path> left = entries(cache);
  ASSERT_EQ(left.size(), 1u);
  EXPECT_EQ(left[0].filename().string().size(), 68u) << left[0];
  EXPECT_EQ(render(dir, scene.gltf, cache.string(), "after").read, 1);
}

// A small MipTexture whose texels depend on `seed`, with both pyramids.
MipTexture small_texture(int seed) {
  MaterialTexels m(8, 8);
  for (std::size_t t = 0; t < m.size(); ++t) m.roughness[t] = 0.1f + 0.8f * float((t * 7 + std::size_t(seed) * 13) % 11) / 10.0f;
  MipTexture texture(m, WrapMode::repeat, WrapMode::repeat, TextureFilter::brdf);
  texture.prepare(TextureFilter::param);
  return texture;
}

// Over its size limit, the cache removes the least recently used entries first; a hit counts as a use.
TEST(MipCache, TheSizeLimitEvictsTheLeastRecentlyUsedEntry) {
  testing::TempDir dir;
  const std::string a(64, 'a'), b(64, 'b'), c(64, 'c');
  std::uint64_t sizes = 0;
  {
    MipCache unlimited(dir / "cache", ~std::uint64_t(0));
    unlimited.store(a, small_texture(1));
    unlimited.store(b, small_texture(2));
    unlimited.store(c, small_texture(3));
    for (const std::string& k : {a, b, c}) sizes += fs::file_size(unlimited.entry_path(k));
    fs::remove(unlimited.entry_path(c));
  }
  // a stored long ago, then b; a read now: b is the least recently used.
  MipCache cache(dir / "cache", sizes - 1);
  const auto now = fs::file_time_type::clock::now();
  fs::last_write_time(cache.entry_path(a), now - std::chrono::hours(2));
  fs::last_write_time(cache.entry_path(b), now - std::chrono::hours(1));
  ASSERT_TRUE(cache.load(a).has_value());
  cache.store(c, small_texture(3));
  EXPECT_TRUE(fs::exists(cache.entry_path(a)));
  EXPECT_FALSE(fs::exists(cache.entry_path(b)));
  EXPECT_TRUE(fs::exists(cache.entry_path(c)));
  EXPECT_TRUE(cache.take_warnings().empty());
}

// `svbrdf-bake mip SCENE` fills the cache ahead of time with the builds the renderer then reads.
TEST(MipCache, BakeFillsTheCacheTheRendererReads) {
  testing::TempDir dir;
  const TextureSetFiles scene = tray(dir / "scene");
  const fs::path cache = dir / "cache";
  const testing::CommandResult bake =
      testing::run_command(std::string("'") + SVBRDF_BAKE + "' mip " + q(scene.gltf) + " --mip-cache " + q(cache), dir.path());
  ASSERT_EQ(bake.status, 0) << bake.err;
  EXPECT_NE(bake.out.find("(0 were there, 1 built)"), std::string::npos) << bake.out;
  const RenderRun run = render(dir, scene.gltf, cache.string(), "render");
  ASSERT_EQ(run.status, 0) << run.err;
  EXPECT_EQ(run.read, 1) << run.err;
  EXPECT_EQ(run.built, 0) << run.err;
  const testing::CommandResult out =
      testing::run_command(std::string("'") + SVBRDF_BAKE + "' mip " + q(scene.gltf) + " --mip-cache off", dir.path());
  EXPECT_EQ(out.status, 2) << out.err;
}

// A cache folder that cannot be made is one warning; the render goes on and writes its image.
TEST(MipCache, AnUnwritableCacheIsAWarning) {
  testing::TempDir dir;
  const TextureSetFiles scene = tray(dir / "scene");
  std::ofstream(dir / "a-file") << "not a folder";
  const RenderRun run = render(dir, scene.gltf, (dir / "a-file" / "cache").string(), "render");
  ASSERT_EQ(run.status, 0) << run.err;
  EXPECT_EQ(count_lines(run.err, "warning: the MIP cache cannot store"), 1) << run.err;
  EXPECT_EQ(run.built, 1) << run.err;
}

}  // namespace
}  // namespace svbrdf
