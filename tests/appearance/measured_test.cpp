// The MERL reader/writer: the layout's index arithmetic against the published layout, a round trip
// of a table written from the gltf model, reciprocity, and every way a file can be bad.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <unistd.h>

#include "appearance/gltf_bsdf.h"
#include "appearance/measured.h"
#include "appearance/rng.h"
#include "base/error.h"
#include "test_models.h"

namespace svbrdf::testing {
namespace {

constexpr double kPiD = 3.14159265358979323846;

// The direction pair of half/difference angles (Rusinkiewicz 1998) built here with rotation
// matrices: d = (sinθd cosφd, sinθd sinφd, cosθd) in the half vector's frame, rotated by θh about
// y then φh about z; wo is d mirrored about the half vector.
void pair_from_half_diff(double th, double td, double pd, double ph, glm::vec3& wi, glm::vec3& wo) {
  const glm::dvec3 d(std::sin(td) * std::cos(pd), std::sin(td) * std::sin(pd), std::cos(td));
  const glm::dvec3 h(std::sin(th) * std::cos(ph), std::sin(th) * std::sin(ph), std::cos(th));
  const glm::dmat3 ry(std::cos(th), 0, -std::sin(th), 0, 1, 0, std::sin(th), 0, std::cos(th));  // columns
  const glm::dmat3 rz(std::cos(ph), std::sin(ph), 0, -std::sin(ph), std::cos(ph), 0, 0, 0, 1);
  const glm::dvec3 a = rz * (ry * d);
  wi = glm::vec3(a);
  wo = glm::vec3(2 * glm::dot(a, h) * h - a);
}

TEST(Merl, CellIndexFollowsThePublishedLayout) {
  // θh = 45° → index ⌊90·sqrt(45/90)⌋ = 63; θd = 10.5° → 10; φd = 100.5° → 100; φh is irrelevant.
  glm::vec3 wi, wo;
  pair_from_half_diff(45 * kPiD / 180, 10.5 * kPiD / 180, 100.5 * kPiD / 180, 0.7, wi, wo);
  EXPECT_EQ(MerlTable::cell_of(wi, wo), 100 + 180 * (10 + 90 * 63));
  // φd and φd + π share a bin (the reciprocity fold): swapping the directions keeps the cell.
  EXPECT_EQ(MerlTable::cell_of(wo, wi), 100 + 180 * (10 + 90 * 63));
  // θh = 10° → ⌊90·sqrt(1/9)⌋ = 30; θd = 60.2° → 60; φd = 3.3° → 3.
  pair_from_half_diff(10 * kPiD / 180, 60.2 * kPiD / 180, 3.3 * kPiD / 180, 2.0, wi, wo);
  EXPECT_EQ(MerlTable::cell_of(wi, wo), 3 + 180 * (60 + 90 * 30));
}

TEST(Merl, RoundTripOfATableWrittenFromGltf) {
  GltfParams g;
  g.base_color = Rgb(0.7f, 0.5f, 0.3f);
  g.roughness = 0.6f;
  const GltfBsdf gltf(g);
  auto table = std::make_shared<MerlTable>(MerlTable::read(gltf_merl_path()));
  const Measured measured(table);
  // At bin centers the value is the model's to float precision (doubles on disk, scaled by the
  // layout's channel factors and back).
  Rng rng(8, 8);
  int checked = 0;
  for (int i = 0; i < 3000; ++i) {
    const int th = static_cast<int>(rng.next_u32() % 90), td = static_cast<int>(rng.next_u32() % 90),
              pd = static_cast<int>(rng.next_u32() % 180);
    glm::vec3 wi, wo;
    MerlTable::center_directions(th, td, pd, wi, wo);
    if (wi.z <= 0.01f || wo.z <= 0.01f) continue;
    ++checked;
    const Rgb a = measured.eval(wi, wo), b = gltf.eval(wi, wo);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(a[c], b[c], 1e-5f * b[c] + 1e-7f) << th << " " << td << " " << pd;
  }
  EXPECT_GT(checked, 1000);
  // Anywhere else it is the value at the center of the direction pair's cell: the quantization.
  for (int i = 0; i < 3000; ++i) {
    const glm::vec3 wi = direction_deg(89 * std::sqrt(rng.next_float()), 360 * rng.next_float());
    const glm::vec3 wo = direction_deg(89 * std::sqrt(rng.next_float()), 360 * rng.next_float());
    const int cell = MerlTable::cell_of(wi, wo);
    const int th = cell / (90 * 180), td = cell / 180 % 90, pd = cell % 180;
    glm::vec3 ci, co;
    MerlTable::center_directions(th, td, pd, ci, co);
    const Rgb expected = gltf.eval(ci, co);
    const Rgb got = measured.eval(wi, wo);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(got[c], expected[c], 1e-5f * expected[c] + 1e-7f);
    EXPECT_EQ(measured.eval(wi, wo), measured.eval(wo, wi)) << "reciprocal exactly";
  }
}

struct TempFile {
  std::filesystem::path path =
      std::filesystem::temp_directory_path() / ("svbrdf_merl_bad_" + std::to_string(::getpid()) + ".binary");
  ~TempFile() {
    std::error_code ec;
    std::filesystem::remove(path, ec);
  }
  void write(const std::vector<char>& bytes) const {
    std::ofstream out(path, std::ios::binary);
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  }
};

std::vector<char> valid_bytes() {
  std::ifstream in(gltf_merl_path(), std::ios::binary);
  return std::vector<char>((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

void expect_bad(const TempFile& f, const std::string& fragment) {
  try {
    MerlTable::read(f.path);
    ADD_FAILURE() << "expected an error containing '" << fragment << "'";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), Error::Kind::bad_input);
    EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find(f.path.string()), std::string::npos) << "names the file: " << e.what();
  }
}

TEST(Merl, BadFilesAreClearErrors) {
  const TempFile f;
  std::vector<char> bytes = valid_bytes();
  ASSERT_EQ(bytes.size(), 12u + 3u * 90 * 90 * 180 * 8);
  f.write(std::vector<char>(bytes.begin(), bytes.begin() + 1000));
  expect_bad(f, "truncated");
  f.write(std::vector<char>(bytes.begin(), bytes.begin() + 5));
  expect_bad(f, "truncated");
  f.write({});
  expect_bad(f, "truncated");
  std::vector<char> trailing = bytes;
  trailing.push_back(0);
  f.write(trailing);
  expect_bad(f, "trailing");
  std::vector<char> dims = bytes;
  const std::int32_t wrong = 91;
  std::memcpy(dims.data(), &wrong, 4);
  f.write(dims);
  expect_bad(f, "dimensions");
  std::vector<char> nan = bytes;
  const double q = NAN;
  std::memcpy(nan.data() + 12 + 8 * 12345, &q, 8);
  f.write(nan);
  expect_bad(f, "not a finite number");
  EXPECT_THROW(MerlTable::read("/nonexistent/dir/table.binary"), Error);
  // Negative entries mean "not measured" in MERL files and read as 0.
  std::vector<char> negative = bytes;
  const double m1 = -1.0;
  std::memcpy(negative.data() + 12 + 8 * 777, &m1, 8);
  f.write(negative);
  EXPECT_EQ(MerlTable::read(f.path).at(777).x, 0.0f);
}

}  // namespace
}  // namespace svbrdf::testing
