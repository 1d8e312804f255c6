// Material files of 8- and 16-bit codes, decoded band by band from the codes (textures/material_files.cpp):
// every code of every channel against the glTF formulas and against decode_material_texels of the
// floats read_image reads; ImageFile's bands of codes.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <vector>

#include "base/error.h"
#include "tests/common/temp_dir.h"
#include "textures/material_loader.h"

namespace svbrdf {
namespace {

using testing::TempDir;

// IEC 61966-2-1's decode, which glTF 2.0 names for baseColorTexture.
double iec_decode(double v) { return v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4); }

// An image holding every code of `bits` bits in every channel: texel p's channel c is code
// (p + c·n/3) mod n, n = 2^bits codes; alpha (channel 3) the same as R. 16² texels for 8 bits, 256² for 16.
struct AllCodes {
  int bits, side, max;
  explicit AllCodes(int b) : bits(b), side(b == 8 ? 16 : 256), max(b == 8 ? 255 : 65535) {}
  int code(int p, int c) const { return c == 3 ? p : (p + c * (max + 1) / 3) % (max + 1); }
  Image image(int channels) const {
    Image img(side, side, channels);
    for (int p = 0; p < side * side; ++p)
      for (int c = 0; c < channels; ++c) img.pixels[std::size_t(p * channels + c)] = float(code(p, c)) / float(max);
    return img;
  }
  void write(const std::filesystem::path& path, int channels) const {
    write_image(path, image(channels), bits == 8 ? PixelFormat::uint8 : PixelFormat::uint16);
  }
};

// A material of every code in `dir`: base colour and metallic-roughness of `channels` channels, the
// normal map of at least 3, with factors other than 1.
MaterialFiles code_set(const AllCodes& codes, const std::filesystem::path& dir, int channels) {
  codes.write(dir / "base.png", channels);
  codes.write(dir / "mr.png", channels);
  codes.write(dir / "normal.png", std::max(channels, 3));
  MaterialFiles f;
  f.base_color = dir / "base.png";
  f.metallic_roughness = dir / "mr.png";
  f.normal = dir / "normal.png";
  f.base_color_factor = {0.7f, 0.9f, 0.35f, 1.0f};
  f.metallic_factor = 0.8f;
  f.roughness_factor = 0.6f;
  f.normal_scale = 1.7f;
  return f;
}

template <class T>
bool same_bits(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0;
}

// glTF 2.0's material decode, texel by texel in double: base colour sRGB-decoded (IEC 61966-2-1) times
// its factor, metallic B and roughness G times theirs, the normal normalize((2·rgb − 1)·(s, s, 1)).
TEST(MaterialCodes, EveryCodeFollowsTheGltfFormulas) {
  const TempDir dir;
  for (const int bits : {8, 16}) {
    const AllCodes codes(bits);
    const MaterialFiles f = code_set(codes, dir.path(), 3);
    ASSERT_EQ(ImageFile(dir / "base.png").code_bits(), bits);
    const MaterialTexels t = load_material_texels(f);
    ASSERT_EQ(t.width, codes.side);
    const double s = f.normal_scale, m = codes.max;
    // Every texel is checked; the first few misses are printed.
    int misses = 0;
    const auto expect_near = [&](double got, double want, int p, const char* what) {
      if (std::abs(got - want) <= 1e-6) return;
      if (++misses <= 5) ADD_FAILURE() << bits << " bits, texel " << p << ", " << what << ": " << got << " against " << want;
    };
    for (int p = 0; p < codes.side * codes.side; ++p) {
      const double v[3] = {codes.code(p, 0) / m, codes.code(p, 1) / m, codes.code(p, 2) / m};
      const double n[3] = {(2 * v[0] - 1) * s, (2 * v[1] - 1) * s, 2 * v[2] - 1};
      const double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
      const std::size_t k = std::size_t(p);
      for (int c = 0; c < 3; ++c) {
        expect_near(t.base_color[k][c], iec_decode(v[c]) * f.base_color_factor[c], p, "base colour");
        expect_near(t.normal[k][c], n[c] / len, p, "normal");
      }
      expect_near(t.metallic[k], v[2] * f.metallic_factor, p, "metallic");
      expect_near(t.roughness[k], v[1] * f.roughness_factor, p, "roughness");
    }
    EXPECT_EQ(misses, 0) << bits << " bits";
  }
}

// The texels from the codes are bit for bit those decode_material_texels makes of the floats
// read_image reads, for gray, gray + alpha, RGB and RGBA files of either width.
TEST(MaterialCodes, EveryCodeDecodesAsItsFloat) {
  const TempDir dir;
  for (const int bits : {8, 16}) {
    const AllCodes codes(bits);
    for (const int channels : {1, 2, 3, 4}) {
      const MaterialFiles f = code_set(codes, dir.path(), channels);
      const MaterialTexels t = load_material_texels(f);
      const Image base = read_image(dir / "base.png"), mr = read_image(dir / "mr.png"), normal = read_image(dir / "normal.png");
      MaterialImages in;
      in.base_color = &base;
      in.base_color_factor = f.base_color_factor;
      in.metallic_roughness = &mr;
      in.metallic_factor = f.metallic_factor;
      in.roughness_factor = f.roughness_factor;
      in.normal = &normal;
      in.normal_scale = f.normal_scale;
      const MaterialTexels want = decode_material_texels(in);
      EXPECT_TRUE(same_bits(t.base_color, want.base_color)) << bits << " bits, " << channels << " channels";
      EXPECT_TRUE(same_bits(t.metallic, want.metallic)) << bits << " bits, " << channels << " channels";
      EXPECT_TRUE(same_bits(t.roughness, want.roughness)) << bits << " bits, " << channels << " channels";
      EXPECT_TRUE(same_bits(t.normal, want.normal)) << bits << " bits, " << channels << " channels";
    }
  }
}

// ImageFile: codes in bands from the top, as the file stores them; floats whole as read_image.
TEST(MaterialCodes, ImageFileReadsCodesInBands) {
  const TempDir dir;
  Image img(3, 5, 2);
  for (std::size_t k = 0; k < img.pixels.size(); ++k) img.pixels[k] = float(k * 1000) / 65535.0f;
  write_image(dir / "codes.png", img, PixelFormat::uint16);
  ImageFile file(dir / "codes.png");
  ASSERT_EQ(file.code_bits(), 16);
  EXPECT_EQ(file.width(), 3);
  EXPECT_EQ(file.height(), 5);
  EXPECT_EQ(file.channels(), 2);
  std::vector<std::uint16_t> top(3 * 2 * 2), rest(3 * 3 * 2);
  file.read_codes(0, 2, top.data());
  file.read_codes(2, 5, rest.data());
  top.insert(top.end(), rest.begin(), rest.end());
  for (std::size_t k = 0; k < top.size(); ++k) EXPECT_EQ(top[k], k * 1000) << k;
  EXPECT_TRUE(same_bits(ImageFile(dir / "codes.png").read().pixels, read_image(dir / "codes.png").pixels));
  // Floats are no codes: read whole.
  write_image(dir / "floats.exr", img, PixelFormat::half);
  ImageFile exr(dir / "floats.exr");
  EXPECT_EQ(exr.code_bits(), 0);
  EXPECT_EQ(exr.stored_format(), PixelFormat::half);
  EXPECT_THROW(exr.read_codes(0, 1, top.data()), Error);
}

// CRC-32 of PNG (ISO 3309), bit by bit: the checksum a damaged chunk needs to pass the chunk checks.
std::uint32_t png_crc(const unsigned char* p, std::size_t n) {
  std::uint32_t c = 0xffffffffu;
  for (std::size_t i = 0; i < n; ++i) {
    c ^= p[i];
    for (int b = 0; b < 8; ++b) c = (c >> 1) ^ (0xedb88320u & (0u - (c & 1u)));
  }
  return ~c;
}

// A file whose chunks are whole and whose pixels are not (its IDAT's zlib stream cut to half, the
// chunk's length and CRC made to match): the decode of its rows fails, and that failure is the one
// reported, naming the file, whichever file decodes first.
TEST(MaterialCodes, ADamagedBandNamesItsFile) {
  const TempDir dir;
  const AllCodes codes(16);
  codes.write(dir / "good.png", 3);
  std::ifstream in(dir / "good.png", std::ios::binary);
  std::vector<unsigned char> png{std::istreambuf_iterator<char>(in), {}};
  const auto be32 = [&](std::size_t at) {
    return std::uint32_t(png[at]) << 24 | std::uint32_t(png[at + 1]) << 16 | std::uint32_t(png[at + 2]) << 8 | png[at + 3];
  };
  const auto put32 = [&](std::size_t at, std::uint32_t v) {
    for (int i = 0; i < 4; ++i) png[at + std::size_t(i)] = (unsigned char)(v >> (24 - 8 * i));
  };
  std::size_t at = 8;
  while (std::memcmp(&png[at + 4], "IDAT", 4) != 0) at += 12 + be32(at);
  const std::uint32_t cut = be32(at) / 2;
  png.erase(png.begin() + std::ptrdiff_t(at + 8 + cut), png.begin() + std::ptrdiff_t(at + 8 + be32(at)));
  put32(at, cut);
  put32(at + 8 + cut, png_crc(&png[at + 4], cut + 4));
  std::ofstream(dir / "cut.png", std::ios::binary).write(reinterpret_cast<const char*>(png.data()), std::streamsize(png.size()));
  ASSERT_EQ(ImageFile(dir / "cut.png").code_bits(), 16);  // its header and chunks pass

  MaterialFiles f;
  f.base_color = dir / "good.png";
  f.metallic_roughness = dir / "cut.png";
  f.normal = dir / "good.png";
  try {
    load_material_texels(f);
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("cut.png"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("cannot decode"), std::string::npos) << e.what();
    EXPECT_EQ(e.exit_code(), 2);
  }
}

}  // namespace
}  // namespace svbrdf
