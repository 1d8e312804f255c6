// Small hostile files, each a few hundred bytes, against svbrdf-render's contract: one line, exit 2,
// promptly — never a signal, an out-of-bounds read, a stack overflow, or gigabytes allocated for a
// size the file merely states. One case per class of attack: byte offsets near 2^64 that would wrap
// a bounds check, deep JSON nesting, cameras whose numbers make NaN rays, numbers too large for an
// int, stated counts and image sizes far beyond the data present, files that are not regular files
// or are huge and sparse. The sanitizer run (make asan) reruns them with ASan and UBSan watching.
#include <gtest/gtest.h>

#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "gltf_test_files.h"
#include "tests/common/test_paths.h"

namespace svbrdf {
namespace {

namespace fs = std::filesystem;

struct RunResult {
  int code = -1;
  bool signalled = false;
  std::string err;
  double seconds = 0;
};

// svbrdf-render on `scene` with a tiny frame, under a wall-clock guard (timeout's exit 124 shows a hang).
RunResult render(const fs::path& scene, const fs::path& dir, const std::string& extra = "") {
  const fs::path err = dir / "err.txt", out = dir / "o.exr";
  const std::string cmd = "timeout 60 '" + std::string(SVBRDF_BINARY_DIR) + "/svbrdf-render' '" + scene.string() +
                          "' --res 8x6 --spp 1 --threads 1 -q -o '" + out.string() + "' " + extra + " > /dev/null 2> '" +
                          err.string() + "'";
  const auto t0 = std::chrono::steady_clock::now();
  const int status = std::system(cmd.c_str());
  RunResult r;
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  r.signalled = !WIFEXITED(status);
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  std::ifstream f(err);
  std::stringstream ss;
  ss << f.rdbuf();
  r.err = ss.str();
  return r;
}

// Exit 2 with exactly one line that contains `expect`, and no image written.
void expect_refused(const RunResult& r, const std::string& expect, const fs::path& dir) {
  ASSERT_FALSE(r.signalled) << r.err;
  EXPECT_EQ(r.code, 2) << r.err;
  std::istringstream lines(r.err);
  int n = 0;
  for (std::string line; std::getline(lines, line);) n += line.find(": warning: ") == std::string::npos;
  EXPECT_EQ(n, 1) << r.err;
  EXPECT_NE(r.err.find(expect), std::string::npos) << "expected '" << expect << "' in: " << r.err;
  EXPECT_FALSE(fs::exists(dir / "o.exr"));
}

std::string replace(std::string s, const std::string& from, const std::string& to) {
  const auto at = s.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) s.replace(at, from.size(), to);
  return s;
}

constexpr const char* kNear2to64 = "18446744073709551600";  // 2^64 − 16: offset + length wraps to a small number

TEST(HostileInput, BufferViewOffsetNear2To64IsRefused) {
  test::TempDir dir;
  const std::string json = replace(test::GltfQuad().json(), R"("byteOffset": 0,)",
                                   std::string(R"("byteOffset": )") + kNear2to64 + ",");
  expect_refused(render(dir.write("s.gltf", json), dir.path()), "bufferViews[0]", dir.path());
}

TEST(HostileInput, AccessorOffsetNear2To64IsRefused) {
  test::TempDir dir;
  const std::string json = replace(test::GltfQuad().json(), R"([{"bufferView": 0, "componentType": 5126,)",
                                   std::string(R"([{"bufferView": 0, "byteOffset": )") + kNear2to64 +
                                       R"(, "componentType": 5126,)");
  expect_refused(render(dir.write("s.gltf", json), dir.path()), "accessors[0]", dir.path());
}

TEST(HostileInput, ImageBufferViewPastItsBufferIsRefused) {
  // A .glb whose image lives in a buffer view that starts 2^64 − 16 bytes in: tinygltf would form a
  // pointer that far into the buffer before any check.
  test::TempDir dir;
  test::GltfQuad q;
  std::vector<unsigned char> bin = q.bytes();
  const std::size_t n = bin.size();
  std::string json = replace(q.json(), R"("uri": ")" + std::string("data:application/octet-stream;base64,") +
                                           test::base64(bin) + R"(", )",
                             "");
  json = replace(json, R"("bufferViews": [)",
                 std::string(R"("bufferViews": [{"buffer": 0, "byteOffset": )") + kNear2to64 +
                     R"(, "byteLength": 32}, )");
  // The image's view is bufferViews[0]; the mesh's shift by one.
  json = replace(json, R"("accessors": [{"bufferView": 0)", R"("accessors": [{"bufferView": 1)");
  json = replace(json, R"({"bufferView": 1, "componentType": 5123)", R"({"bufferView": 2, "componentType": 5123)");
  json.pop_back();
  json += R"(, "images": [{"bufferView": 0, "mimeType": "image/png"}], "textures": [{"source": 0}]})";
  (void)n;
  const fs::path glb = dir.write_bytes("s.glb", test::make_glb(json, bin));
  expect_refused(render(glb, dir.path()), "bufferViews[0]", dir.path());
}

TEST(HostileInput, GlbChunkLengthPastTheFileIsRefused) {
  test::TempDir dir;
  std::vector<unsigned char> glb = test::make_glb(test::GltfQuad().json(), {});
  for (int i = 0; i < 4; ++i) glb[12 + i] = 0xF0;  // the JSON chunk claims 0xF0F0F0F0 bytes
  expect_refused(render(dir.write_bytes("s.glb", glb), dir.path()), "JSON chunk", dir.path());
}

TEST(HostileInput, DeeplyNestedJsonIsRefusedBeforeParsing) {
  // 20,000 nested arrays in `extras`: tinygltf's recursive conversion overflows the stack.
  test::TempDir dir;
  const std::string deep = std::string(20000, '[') + std::string(20000, ']');
  test::GltfQuad q;
  q.top_extra = R"(, "extras": )" + deep;
  expect_refused(render(dir.write("s.gltf", q.json()), dir.path()), "nests deeper", dir.path());
  const fs::path glb = dir.write_bytes("s.glb", test::make_glb(q.json(), {}));
  expect_refused(render(glb, dir.path()), "nests deeper", dir.path());
}

TEST(HostileInput, SingularCameraNodeIsRefused) {
  test::TempDir dir;
  test::GltfQuad q;
  q.nodes = R"([{"mesh": 0}, {"camera": 0, "matrix": [0,0,0,0, 0,0,0,0, 0,0,0,0, 0,0,2,1]}])";
  q.scene_nodes = "[0, 1]";
  q.top_extra = R"(, "cameras": [{"type": "perspective", "perspective": {"yfov": 0.8, "znear": 0.01}}])";
  expect_refused(render(dir.write("s.gltf", q.json()), dir.path()), "singular", dir.path());
}

TEST(HostileInput, OrthographicCameraOfExtremeExtentIsRefused) {
  test::TempDir dir;
  for (const char* mag : {"1e38", "1e-40"}) {
    test::GltfQuad q;
    q.nodes = R"([{"mesh": 0}, {"camera": 0, "translation": [0, 0, 2]}])";
    q.scene_nodes = "[0, 1]";
    q.top_extra = std::string(R"(, "cameras": [{"type": "orthographic", "orthographic": {"xmag": )") + mag +
                  R"(, "ymag": 1, "znear": 0.01, "zfar": 10}}])";
    expect_refused(render(dir.write("s.gltf", q.json()), dir.path()), "xmag", dir.path());
  }
}

TEST(HostileInput, NumbersBeyondIntAreRefusedByName) {
  test::TempDir dir;
  // An index of 2^33: tinygltf keeps indices in an int, where it would become bufferViews[0].
  const std::string json = replace(test::GltfQuad().json(), R"({"bufferView": 1, "componentType": 5123)",
                                   R"({"bufferView": 8589934592, "componentType": 5123)");
  expect_refused(render(dir.write("i.gltf", json), dir.path()), "accessors[1].bufferView", dir.path());
  // 1e+20 as an extension's texture index: converting it to int is undefined behaviour.
  test::GltfQuad q;
  q.materials = R"([{"extensions": {"KHR_materials_specular": {"specularTexture": {"index": 1e+20}}}}])";
  q.primitive_extra = R"(, "material": 0)";
  q.top_extra = R"(, "extensionsUsed": ["KHR_materials_specular"])";
  expect_refused(render(dir.write("s.gltf", q.json()), dir.path()), "specularTexture.index", dir.path());
}

TEST(HostileInput, StatedCountsBeyondTheDataAreRefusedWithoutAllocating) {
  test::TempDir dir;
  {  // a count of 10^9 over a 48-byte buffer view
    test::GltfQuad q;
    q.position_count = 1000000000;
    const RunResult r = render(dir.write("a.gltf", q.json()), dir.path());
    expect_refused(r, "accessors[0]", dir.path());
  }
  {  // 10^9 zeros with no buffer view, sparse over one element
    test::GltfQuad q;
    std::string json = replace(q.json(), R"([{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3"})",
                               R"([{"componentType": 5126, "count": 1000000000, "type": "VEC3", "sparse": )"
                               R"({"count": 1, "indices": {"bufferView": 1, "componentType": 5123}, )"
                               R"("values": {"bufferView": 0}}})");
    expect_refused(render(dir.write("b.gltf", json), dir.path()), "accessors[0]", dir.path());
  }
}

TEST(HostileInput, FilesThatAreNotRegularOrAreHugeAndSparseAreRefusedUnread) {
  test::TempDir dir;
  // A buffer file of 2 GiB (sparse: no disk used) whose byteLength says 56.
  const fs::path big = dir.path() / "big.bin";
  { std::ofstream(big) << ""; }
  fs::resize_file(big, std::uintmax_t(2) << 30);
  test::GltfQuad q;
  q.buffer_uri = "big.bin";
  RunResult r = render(dir.write("s.gltf", q.json()), dir.path());
  expect_refused(r, "byteLength", dir.path());
  EXPECT_LT(r.seconds, 30.0) << "the 2 GiB file was read";  // reading it is minutes under ASan, a second here
  // The scene file itself 2 GiB of zeros: refused at its first byte.
  const fs::path zeros = dir.path() / "zeros.gltf";
  { std::ofstream(zeros) << ""; }
  fs::resize_file(zeros, std::uintmax_t(2) << 30);
  r = render(zeros, dir.path());
  expect_refused(r, "byte 0", dir.path());
  fs::remove(zeros);
  // A buffer that names a FIFO: opening it for reading would wait for a writer forever.
  const fs::path fifo = dir.path() / "fifo.bin";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  q.buffer_uri = "fifo.bin";
  expect_refused(render(dir.write("f.gltf", q.json()), dir.path()), "not a regular file", dir.path());
  fs::remove(big);
}

}  // namespace
}  // namespace svbrdf
