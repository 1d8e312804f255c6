// Corrupt files as users meet them — a truncated download, flipped bytes in a buffer, a damaged
// .glb or JSON text — made from the sample models by seeded random mutation: svbrdf-render exits 0
// (the damage was legal) or 2 with one line of well-formed UTF-8 and no output file; never a crash,
// a hang, or raw bytes on the terminal. (Fuzzing 1 150 such mutations found one fault, raw bytes of
// the file in the line; this test keeps the whole property.)
#include <gtest/gtest.h>

#include <sys/wait.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "appearance/rng.h"
#include "base/message_line.h"
#include "gltf_samples.h"
#include "gltf_test_files.h"
#include "tests/common/test_paths.h"

namespace svbrdf {
namespace {

namespace fs = std::filesystem;

std::string read_bytes(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

struct Model {
  const char* dir;   // under the samples folder
  const char* file;  // the scene file in it
};

// Small models, so a run takes a fraction of a second: JSON with a .bin, and .glb.
constexpr Model kModels[] = {
    {"BoxTextured/glTF", "BoxTextured.gltf"},
    {"BoxTextured/glTF-Binary", "BoxTextured.glb"},
    {"VertexColorTest/glTF-Binary", "VertexColorTest.glb"},
    {"OrientationTest/glTF-Binary", "OrientationTest.glb"},
    {"MultiUVTest/glTF", "MultiUVTest.gltf"},
    {"TextureTransformTest/glTF", "TextureTransformTest.gltf"},
};

TEST(CorruptInput, EveryDamagedSampleIsRenderedOrRefusedInOneLine) {
  if (!fs::exists(test::samples_dir()))
    GTEST_SKIP() << "the glTF sample models are not here (" << test::samples_dir() << "); a clone without ../shared";
  Rng rng(2026, 11);
  constexpr int kCases = 36;
  int refused = 0;
  for (int c = 0; c < kCases; ++c) {
    const Model& m = kModels[rng.next_u32() % std::size(kModels)];
    test::TempDir dir;
    const fs::path work = dir.path() / "model";
    fs::copy(test::samples_dir() / m.dir, work, fs::copy_options::recursive);
    for (const auto& e : fs::directory_iterator(work))
      fs::permissions(e.path(), fs::perms::owner_read | fs::perms::owner_write, fs::perm_options::add);
    // The file to damage: the scene file or one of its buffers.
    std::vector<fs::path> targets;
    for (const auto& e : fs::directory_iterator(work))
      if (e.path().extension() == ".gltf" || e.path().extension() == ".glb" || e.path().extension() == ".bin")
        targets.push_back(e.path());
    std::sort(targets.begin(), targets.end());
    const fs::path target = targets[rng.next_u32() % targets.size()];
    std::string bytes = read_bytes(target);
    ASSERT_FALSE(bytes.empty()) << target;
    std::string what;
    if (rng.next_u32() % 3 == 0) {
      bytes.resize(rng.next_u32() % bytes.size());
      what = "truncated to " + std::to_string(bytes.size()) + " bytes";
    } else {
      const int flips = 1 << (2 * (rng.next_u32() % 4));  // 1, 4, 16 or 64 bytes
      for (int k = 0; k < flips; ++k) bytes[rng.next_u32() % bytes.size()] = char(rng.next_u32() & 0xFF);
      what = std::to_string(flips) + " bytes overwritten";
    }
    std::ofstream(target, std::ios::binary | std::ios::trunc) << bytes;
    const std::string label = std::string(m.dir) + "/" + target.filename().string() + ", " + what + " (case " +
                              std::to_string(c) + ")";

    const fs::path out = dir.path() / "o.exr", err = dir.path() / "err.txt";
    const std::string cmd = "timeout 120 '" + std::string(SVBRDF_BINARY_DIR) + "/svbrdf-render' '" +
                            (work / m.file).string() + "' --res 16x12 --spp 1 --threads 1 -q -o '" + out.string() +
                            "' > /dev/null 2> '" + err.string() + "'";
    const int status = std::system(cmd.c_str());
    ASSERT_TRUE(WIFEXITED(status)) << label << ": killed by a signal";
    const int code = WEXITSTATUS(status);
    ASSERT_TRUE(code == 0 || code == 2) << label << ": exit " << code << "\n" << read_bytes(err);
    const std::string text = read_bytes(err);
    for (std::size_t i = 0; i < text.size();) {
      const std::size_t n = text[i] == '\n' ? 1 : kept_length(text, i);  // lines end in '\n'
      ASSERT_GT(n, 0u) << label << ": byte " << i << " is not UTF-8 text in: " << text;
      i += n;
    }
    if (code == 2) {
      ++refused;
      int errors = 0;
      std::istringstream lines(text);
      for (std::string line; std::getline(lines, line);)
        if (line.find(": warning: ") == std::string::npos) ++errors;
      EXPECT_EQ(errors, 1) << label << ":\n" << text;
      EXPECT_FALSE(fs::exists(out)) << label << ": an output file for refused input";
    } else {
      EXPECT_TRUE(fs::exists(out)) << label;
    }
  }
  // Most damaged files are refused (30 of the 36 when this was written; 7 of those lines quoted bytes
  // that are not UTF-8, escaped since): a loader that accepted everything would not be tested here.
  EXPECT_GE(refused, kCases / 3);
}

}  // namespace
}  // namespace svbrdf
