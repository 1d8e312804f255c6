#include "textures/image.h"

#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>
#include <thread>

#include "base/error.h"
#include "base/resource_limits.h"
#include "tests/common/temp_dir.h"

namespace svbrdf {
namespace {

namespace fs = std::filesystem;
using testing::TempDir;

Image gradient(int w, int h, int c) {
  Image img(w, h, c);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int k = 0; k < c; ++k) img.at(x, y, k) = float(x + 3 * y + 7 * k) / float(w + 3 * h + 7 * c);
  return img;
}

std::vector<std::byte> file_bytes(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  std::vector<char> chars((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
  std::vector<std::byte> out(chars.size());
  for (std::size_t i = 0; i < chars.size(); ++i) out[i] = std::byte(static_cast<unsigned char>(chars[i]));
  return out;
}

void write_bytes(const fs::path& p, const std::vector<std::byte>& bytes) {
  std::ofstream f(p, std::ios::binary);
  f.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
}

// Expects fn to throw svbrdf::Error with exit code 2 whose message names `needle`.
template <class Fn>
void expect_bad_input(Fn fn, const std::string& needle) {
  try {
    fn();
    ADD_FAILURE() << "no error; expected one naming " << needle;
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
    EXPECT_EQ(e.exit_code(), 2) << e.what();
    EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << "not one line: " << e.what();
  }
}

// An OpenEXR float image comes back bit-identical; a 16-bit PNG to within its quantization.
TEST(Image, RoundTripThroughOpenImageIO) {
  const TempDir dir;
  const Image src = gradient(17, 9, 3);

  write_image(dir / "g.exr", src, PixelFormat::float32);
  const Image exr = read_image(dir / "g.exr");
  ASSERT_EQ(exr.width, 17);
  ASSERT_EQ(exr.height, 9);
  ASSERT_EQ(exr.channels, 3);
  EXPECT_EQ(exr.pixels, src.pixels);

  write_image(dir / "g.png", src, PixelFormat::uint16);
  const Image png = read_image(dir / "g.png");
  ASSERT_EQ(png.pixels.size(), src.pixels.size());
  for (std::size_t i = 0; i < src.pixels.size(); ++i) EXPECT_NEAR(png.pixels[i], src.pixels[i], 0.5 / 65535 + 1e-7);
}

// Every format the project reads and writes, in gray, RGB and RGBA where the format holds them,
// comes back within its quantization: half 2^-11 relative, 8/16-bit half a code, RGBE 1 % (8-bit
// shared exponent), JPEG a few codes (lossy; averaged error).
TEST(Image, RoundTripsEveryFormatAndChannelCount) {
  const TempDir dir;
  struct Case {
    const char* ext;
    PixelFormat format;
    std::vector<int> channels;
    double abs_tol, rel_tol, mean_tol;
    PixelFormat stored;
  };
  const std::vector<Case> cases = {
      {".png", PixelFormat::uint8, {1, 2, 3, 4}, 0.5 / 255 + 1e-7, 0, 0, PixelFormat::uint8},
      {".png", PixelFormat::uint16, {1, 3, 4}, 0.5 / 65535 + 1e-7, 0, 0, PixelFormat::uint16},
      {".exr", PixelFormat::half, {1, 3, 4}, 1e-7, 1.0 / 2048, 0, PixelFormat::half},
      {".exr", PixelFormat::float32, {1, 3, 4}, 0, 0, 0, PixelFormat::float32},
      {".tif", PixelFormat::uint8, {1, 3, 4}, 0.5 / 255 + 1e-7, 0, 0, PixelFormat::uint8},
      {".tif", PixelFormat::uint16, {3}, 0.5 / 65535 + 1e-7, 0, 0, PixelFormat::uint16},
      {".tif", PixelFormat::float32, {3}, 0, 0, 0, PixelFormat::float32},
      {".hdr", PixelFormat::float32, {3}, 1e-6, 0.01, 0, PixelFormat::float32},
      {".jpg", PixelFormat::uint8, {1, 3}, 0.1, 0, 0.01, PixelFormat::uint8},
  };
  for (const Case& c : cases) {
    for (int ch : c.channels) {
      SCOPED_TRACE(std::string(c.ext) + " channels " + std::to_string(ch) + " format " + std::to_string(int(c.format)));
      const Image src = gradient(32, 16, ch);
      const fs::path file = dir / ("img" + std::to_string(ch) + "_" + std::to_string(int(c.format)) + c.ext);
      write_image(file, src, c.format);
      PixelFormat stored{};
      const Image back = read_image(file, &stored);
      EXPECT_EQ(stored, c.stored);
      ASSERT_EQ(back.width, src.width);
      ASSERT_EQ(back.height, src.height);
      ASSERT_EQ(back.channels, src.channels);
      double sum = 0;
      for (std::size_t i = 0; i < src.pixels.size(); ++i) {
        const double err = std::abs(double(back.pixels[i]) - src.pixels[i]);
        sum += err;
        // Relative to the pixel's largest channel: RGBE shares one exponent per pixel.
        float pixel_max = 0;
        for (std::size_t k = i - i % std::size_t(ch); k < i - i % std::size_t(ch) + std::size_t(ch); ++k)
          pixel_max = std::max(pixel_max, std::abs(src.pixels[k]));
        EXPECT_LE(err, c.abs_tol + c.rel_tol * pixel_max) << "at " << i;
      }
      if (c.mean_tol > 0) {
        EXPECT_LE(sum / double(src.pixels.size()), c.mean_tol);
      }
    }
  }
}

TEST(Image, MissingFileIsAnErrorNamingIt) {
  expect_bad_input([] { read_image("/nonexistent/dir/missing.png"); }, "missing.png");
}

// A file cut in half, or garbage behind a valid extension, is bad input naming the file.
TEST(Image, TruncatedOrCorruptFilesAreErrorsNamingThem) {
  const TempDir dir;
  const Image src = gradient(64, 64, 3);
  for (const char* name : {"cut.png", "cut.exr", "cut.jpg", "cut.tif"}) {
    SCOPED_TRACE(name);
    write_image(dir / name, src, std::string(name).ends_with(".exr") ? PixelFormat::half : PixelFormat::uint8);
    std::vector<std::byte> bytes = file_bytes(dir / name);
    bytes.resize(bytes.size() / 2);
    write_bytes(dir / name, bytes);
    expect_bad_input([&] { read_image(dir / name); }, name);
  }
  std::vector<std::byte> garbage(300);
  for (std::size_t i = 0; i < garbage.size(); ++i) garbage[i] = std::byte((i * 37 + 11) & 0xff);
  write_bytes(dir / "garbage.png", garbage);
  expect_bad_input([&] { read_image(dir / "garbage.png"); }, "garbage.png");
  write_bytes(dir / "empty.png", {});
  expect_bad_input([&] { read_image(dir / "empty.png"); }, "empty.png");
  expect_bad_input([&] { read_image(dir.path()); }, dir.path().filename().string());
}

std::uint32_t crc32(const std::byte* p, std::size_t n) {
  std::uint32_t c = 0xffffffffu;
  for (std::size_t i = 0; i < n; ++i) {
    c ^= std::to_integer<std::uint32_t>(p[i]);
    for (int k = 0; k < 8; ++k) c = (c >> 1) ^ (0xedb88320u & (0u - (c & 1u)));
  }
  return ~c;
}

// `png` with its IHDR made to claim side × side pixels: 8-byte signature, 4 length, "IHDR", width,
// height (big-endian), ..., CRC over type and data.
void claim_size(std::vector<std::byte>& png, std::uint32_t side) {
  for (int k = 0; k < 2; ++k)
    for (int b = 0; b < 4; ++b) png[16 + 4 * k + b] = std::byte((side >> (24 - 8 * b)) & 0xffu);
  const std::uint32_t crc = crc32(png.data() + 12, 17);
  for (int b = 0; b < 4; ++b) png[29 + b] = std::byte((crc >> (24 - 8 * b)) & 0xffu);
}

// A PNG whose header claims 100000 × 100000 pixels is refused before any pixel is allocated;
// an empty image cannot be written.
TEST(Image, AbsurdAndEmptySizesAreRefused) {
  const TempDir dir;
  write_image(dir / "one.png", gradient(1, 1, 3), PixelFormat::uint8);
  std::vector<std::byte> png = file_bytes(dir / "one.png");
  claim_size(png, 100000);
  write_bytes(dir / "huge.png", png);
  expect_bad_input([&] { read_image(dir / "huge.png"); }, "huge.png");
  expect_bad_input([&] { read_image_from_memory(png, "image/png", "images[7]"); }, "images[7]");

  expect_bad_input([&] { write_image(dir / "empty.png", Image(0, 0, 3), PixelFormat::uint8); }, "empty.png");
  EXPECT_FALSE(fs::exists(dir / "empty.png"));
  expect_bad_input([] { check_image_size("x", 0, 5); }, "no pixels");
  expect_bad_input([] { check_image_size("x", kMaxImageSide + 1, 1); }, "beyond");
  expect_bad_input([] { check_image_size("x", 20000, 20000); }, "beyond");  // 4·10^8 > 2^28 texels
  EXPECT_NO_THROW(check_image_size("x", kMaxImageSide, 1));
}

// A PNG whose compressed data is damaged under valid CRCs (it fails inside libpng, whose default handler
// prints its own "libpng error: ..." line).
std::vector<std::byte> damaged_png(const TempDir& dir) {
  write_image(dir / "ok.png", gradient(16, 16, 3), PixelFormat::uint8);
  std::vector<std::byte> png = file_bytes(dir / "ok.png");
  bool damaged = false;
  for (std::size_t at = 8; at + 12 <= png.size();) {
    const std::uint32_t n = std::to_integer<std::uint32_t>(png[at]) << 24 | std::to_integer<std::uint32_t>(png[at + 1]) << 16 |
                            std::to_integer<std::uint32_t>(png[at + 2]) << 8 | std::to_integer<std::uint32_t>(png[at + 3]);
    if (std::memcmp(png.data() + at + 4, "IDAT", 4) == 0) {
      for (std::size_t k = 2; k < n; k += 3) png[at + 8 + k] ^= std::byte{0x5a};
      const std::uint32_t crc = crc32(png.data() + at + 4, n + 4);
      for (int b = 0; b < 4; ++b) png[at + 8 + n + b] = std::byte((crc >> (24 - 8 * b)) & 0xffu);
      damaged = true;
    }
    at += 12 + n;
  }
  EXPECT_TRUE(damaged);
  return png;
}

// The error must come back only as the thrown message (the programs print one line).
TEST(Image, DamagedPngDataPrintsNothingOfItsOwn) {
  const TempDir dir;
  const std::vector<std::byte> png = damaged_png(dir);
  ::testing::internal::CaptureStderr();
  expect_bad_input([&] { read_image_from_memory(png, "image/png", "images[1]"); }, "images[1]");
  EXPECT_EQ(::testing::internal::GetCapturedStderr(), "");
}

// PNGs decode in parallel: damaged ones among good ones, on several threads at once, print nothing of
// their own while any decode runs, and stderr is the program's again once they are all done.
TEST(Image, PngsDecodedInParallelPrintNothingAndGiveStderrBack) {
  const TempDir dir;
  const std::vector<std::byte> bad = damaged_png(dir);
  const std::vector<std::byte> good = file_bytes(dir / "ok.png");
  ::testing::internal::CaptureStderr();
  std::vector<std::thread> threads;
  std::atomic<int> refused{0}, read{0};
  for (int t = 0; t < 8; ++t)
    threads.emplace_back([&, t] {
      for (int k = 0; k < 20; ++k) {
        try {
          if ((t + k) % 2) read_image_from_memory(bad, "image/png", "bad");
          else if (read_image_from_memory(good, "image/png", "good").width == 16) ++read;
        } catch (const Error&) {
          ++refused;
        }
      }
    });
  for (std::thread& t : threads) t.join();
  std::fputs("after\n", stderr);
  EXPECT_EQ(::testing::internal::GetCapturedStderr(), "after\n");
  EXPECT_EQ(refused.load(), 80);
  EXPECT_EQ(read.load(), 80);
}

// A 16384² PNG header (a file of a few dozen bytes) is within the per-side limit but over the default
// --max-texels (2^26): refused from the header, before 4 GiB of floats are allocated. The limit is the
// process's (base/resource_limits.h): lowered, it refuses a 16×16 image; restored, it reads it.
TEST(Image, TexelLimitIsCheckedFromTheHeader) {
  const TempDir dir;
  write_image(dir / "small.png", gradient(16, 16, 3), PixelFormat::uint8);
  std::vector<std::byte> png = file_bytes(dir / "small.png");
  claim_size(png, 16384);
  write_bytes(dir / "big.png", png);
  expect_bad_input([&] { read_image(dir / "big.png"); }, "--max-texels");
  expect_bad_input([&] { read_image_from_memory(png, "image/png", "images[2]"); }, "--max-texels");

  const std::uint64_t saved = resource_limits().max_texels;
  resource_limits().max_texels = 255;
  expect_bad_input([&] { read_image(dir / "small.png"); }, "--max-texels");
  resource_limits().max_texels = 256;
  EXPECT_NO_THROW(read_image(dir / "small.png"));
  resource_limits().max_texels = saved;
}

// OpenEXR allocates an attribute's value at the size the file states before reading it: an EXR of a
// few hundred bytes whose first attribute states 2^31 - 1 bytes (its layout: the 4-byte magic, the
// 4-byte version field, then the attribute's name and type name, null-terminated, and its 4-byte
// little-endian size) is refused from the header, from a file and from memory, with one line; with the
// size restored it reads.
TEST(Image, ExrAttributeLargerThanTheFileIsRefusedFromTheHeader) {
  const TempDir dir;
  write_image(dir / "small.exr", gradient(4, 4, 3), PixelFormat::half);
  std::vector<std::byte> exr = file_bytes(dir / "small.exr");
  std::size_t at = 8;
  while (exr.at(at) != std::byte{0}) ++at;
  ++at;
  while (exr.at(at) != std::byte{0}) ++at;
  ++at;
  const std::vector<std::byte> size(exr.begin() + std::ptrdiff_t(at), exr.begin() + std::ptrdiff_t(at) + 4);
  for (int b = 0; b < 4; ++b) exr[at + std::size_t(b)] = std::byte(b == 3 ? 0x7f : 0xff);
  write_bytes(dir / "lying.exr", exr);
  expect_bad_input([&] { read_image(dir / "lying.exr"); }, "states 2147483647 bytes");
  expect_bad_input([&] { read_image_from_memory(exr, "", "images[4]"); }, "images[4]: corrupt OpenEXR header");
  std::copy(size.begin(), size.end(), exr.begin() + std::ptrdiff_t(at));
  EXPECT_EQ(read_image_from_memory(exr, "", "images[4]").pixels, read_image(dir / "small.exr").pixels);
}

// Decoding from memory (a .glb buffer view, a data: URI) gives exactly what decoding the file
// gives, for every format glTF embeds and for the float formats.
TEST(Image, DecodesFromMemoryLikeFromFile) {
  const TempDir dir;
  const Image src = gradient(20, 12, 3);
  for (const char* name : {"m.png", "m.jpg", "m.exr", "m.tif", "m.hdr"}) {
    SCOPED_TRACE(name);
    const fs::path file = dir / name;
    write_image(file, src, std::string(name).ends_with(".exr") || std::string(name).ends_with(".hdr") ? PixelFormat::float32 : PixelFormat::uint8);
    const Image from_file = read_image(file);
    const std::vector<std::byte> bytes = file_bytes(file);
    // The signature decides; a wrong or absent MIME type does not matter.
    for (const char* mime : {"", "image/png", "image/jpeg", "application/octet-stream"}) {
      const Image from_memory = read_image_from_memory(bytes, mime, "buffer");
      EXPECT_EQ(from_memory.width, from_file.width);
      EXPECT_EQ(from_memory.channels, from_file.channels);
      EXPECT_EQ(from_memory.pixels, from_file.pixels);
    }
    // A file name works as the hint too.
    EXPECT_EQ(read_image_from_memory(bytes, name, "buffer").pixels, from_file.pixels);
  }
  expect_bad_input([] { read_image_from_memory({}, "image/png", "scene.glb: images[0]"); }, "scene.glb: images[0]");
  std::vector<std::byte> garbage(100, std::byte(0x42));
  expect_bad_input([&] { read_image_from_memory(garbage, "image/png", "scene.glb: images[1]"); }, "scene.glb: images[1]");
  expect_bad_input([&] { read_image_from_memory(garbage, "image/webp", "images[2]"); }, "images[2]");
  std::vector<std::byte> png = file_bytes(dir / "m.png");
  png.resize(png.size() / 2);
  expect_bad_input([&] { read_image_from_memory(png, "image/png", "images[3]"); }, "images[3]");
}

std::vector<std::byte> bytes_of(std::string_view s) {
  std::vector<std::byte> b;
  for (char c : s) b.push_back(std::byte(static_cast<unsigned char>(c)));
  return b;
}

// RFC 4648 §10 test vectors, both ways; RFC 2397 data: URIs with base64 and %-escapes.
TEST(Image, Base64AndDataUris) {
  const std::pair<const char*, const char*> vectors[] = {{"", ""},         {"f", "Zg=="},         {"fo", "Zm8="},
                                                         {"foo", "Zm9v"},  {"foob", "Zm9vYg=="}, {"fooba", "Zm9vYmE="},
                                                         {"foobar", "Zm9vYmFy"}};
  for (const auto& [plain, encoded] : vectors) {
    EXPECT_EQ(encode_base64(bytes_of(plain)), encoded);
    const DataUri uri = decode_data_uri(std::string("data:application/octet-stream;base64,") + encoded, "t");
    EXPECT_EQ(uri.mime_type, "application/octet-stream");
    EXPECT_EQ(uri.bytes, bytes_of(plain)) << encoded;
  }
  const DataUri text = decode_data_uri("data:text/plain;charset=US-ASCII,a%20b%2Cc", "t");
  EXPECT_EQ(text.mime_type, "text/plain");
  EXPECT_EQ(text.bytes, bytes_of("a b,c"));
  EXPECT_TRUE(is_data_uri("data:,"));
  EXPECT_FALSE(is_data_uri("texture.png"));

  // A PNG inside a data: URI decodes like the file.
  const TempDir dir;
  write_image(dir / "u.png", gradient(5, 4, 4), PixelFormat::uint8);
  const std::vector<std::byte> png = file_bytes(dir / "u.png");
  const DataUri png_uri = decode_data_uri("data:image/png;base64," + encode_base64(png), "images[0].uri");
  EXPECT_EQ(png_uri.mime_type, "image/png");
  EXPECT_EQ(read_image_from_memory(png_uri.bytes, png_uri.mime_type, "images[0]").pixels, read_image(dir / "u.png").pixels);

  expect_bad_input([] { decode_data_uri("data:image/png;base64,Zm9v!mFy", "images[4].uri"); }, "images[4].uri");
  expect_bad_input([] { decode_data_uri("data:image/png;base64,Zm9vY", "images[5].uri"); }, "images[5].uri");
  expect_bad_input([] { decode_data_uri("data:image/png;base64", "images[6].uri"); }, "images[6].uri");
  expect_bad_input([] { decode_data_uri("data:,a%2", "images[7].uri"); }, "images[7].uri");
}

}  // namespace
}  // namespace svbrdf
