// The description of a texture cache image file (render/image_file_description.h): the code tables
// come back bit for bit whatever floats they hold (−0, subnormals, infinities, NaN payloads: random
// bit patterns), and a description that is garbled, cut short, another key's or not whole is refused.
#include <gtest/gtest.h>

#include <bit>
#include <cstdint>
#include <random>
#include <string>

#include "base/sha256.h"
#include "render/image_file_description.h"

namespace svbrdf {
namespace {

const std::string kKey(64, 'a');

ImageFileDescription random_codes(std::uint32_t seed, bool linear) {
  std::mt19937 rng(seed);
  ImageFileDescription d;
  d.key = kKey;
  d.width = 300, d.height = 17, d.channels = 3;
  d.codes = true, d.linear = linear;
  for (CodeTable* t : {&d.raw_table, &d.linear_table})
    for (auto& channel : *t)
      for (float& v : channel) v = std::bit_cast<float>(std::uint32_t(rng()));
  // The values whose decimal or arithmetic round trip is most easily lost.
  d.raw_table[0][0] = -0.0f;
  d.raw_table[0][1] = std::bit_cast<float>(0x00000001u);  // the least subnormal
  d.raw_table[0][2] = std::bit_cast<float>(0x7fc12345u);  // a quiet NaN with a payload
  d.raw_table[0][3] = std::bit_cast<float>(0xff800000u);  // −∞
  d.raw_table[3][255] = 1.0f / 3.0f;
  return d;
}

void expect_same_bits(const CodeTable& a, const CodeTable& b) {
  for (std::size_t c = 0; c < 4; ++c)
    for (std::size_t k = 0; k < 256; ++k)
      ASSERT_EQ(std::bit_cast<std::uint32_t>(a[c][k]), std::bit_cast<std::uint32_t>(b[c][k])) << c << " " << k;
}

TEST(ImageFileDescription, CodeTablesComeBackBitForBit) {
  for (std::uint32_t seed = 1; seed <= 4; ++seed)
    for (const bool linear : {false, true}) {
      const ImageFileDescription d = random_codes(seed, linear);
      std::string why;
      const auto back = parse_image_file_description(describe(d), kKey, &why);
      ASSERT_TRUE(back) << why;
      EXPECT_EQ(back->key, kKey);
      EXPECT_EQ(back->width, 300);
      EXPECT_EQ(back->height, 17);
      EXPECT_EQ(back->channels, 3);
      EXPECT_TRUE(back->codes);
      EXPECT_EQ(back->linear, linear);
      expect_same_bits(back->raw_table, d.raw_table);
      if (linear) expect_same_bits(back->linear_table, d.linear_table);
    }
  ImageFileDescription floats;
  floats.key = kKey;
  floats.width = 1, floats.height = 4096, floats.channels = 1;
  const auto back = parse_image_file_description(describe(floats), kKey, nullptr);
  ASSERT_TRUE(back);
  EXPECT_FALSE(back->codes);
  EXPECT_EQ(back->width, 1);
  EXPECT_EQ(back->height, 4096);
  EXPECT_EQ(back->channels, 1);
}

// `text` with its digest line made again for its body: what is refused then is refused for what the
// body says, not for the digest.
std::string redigested(std::string text) {
  const std::size_t at = text.rfind("sha256 ");
  text.resize(at);
  return text + "sha256 " + to_hex(sha256(text)) + "\n";
}

TEST(ImageFileDescription, GarbledCutOrForeignDescriptionsAreRefused) {
  const std::string good = describe(random_codes(7, true));
  const auto refused = [&](const std::string& text, const std::string& key, const std::string& what) {
    std::string why;
    EXPECT_FALSE(parse_image_file_description(text, key, &why)) << what;
    EXPECT_FALSE(why.empty()) << what;
  };
  refused("", kKey, "empty");
  refused(good, std::string(64, 'b'), "another key's");
  std::string flipped = good;
  char& digit = flipped[flipped.find("\nraw ") + 9];
  digit = digit == '0' ? '1' : '0';  // a hexadecimal digit of the table, another one
  refused(flipped, kKey, "a digit of the table changed");
  refused(good.substr(0, good.size() / 2), kKey, "cut in half");
  refused(good.substr(0, good.size() - 1), kKey, "its last line break gone");
  // Bodies that are not whole under a digest that matches them.
  std::string short_table = good;
  short_table.erase(short_table.find("\nraw ") + 5, 8);
  refused(redigested(short_table), kKey, "a table one value short");
  std::string not_hex = good;
  not_hex[not_hex.find("\nraw ") + 5] = 'z';
  refused(redigested(not_hex), kKey, "a table digit that is not hexadecimal");
  std::string upper = good;
  upper.replace(upper.find("\nimage "), 7, "\nimagE ");
  refused(redigested(upper), kKey, "no image line");
  std::string no_size = good;
  no_size.replace(no_size.find("\nimage 300x17x3\n"), 16, "\nimage 300x0x3\n");
  refused(redigested(no_size), kKey, "a zero height");
  std::string wide = good;
  wide.replace(wide.find("\nimage 300x17x3\n"), 16, "\nimage 300x17x5\n");
  refused(redigested(wide), kKey, "five channels");
  std::string extra = good;
  extra.insert(extra.rfind("sha256 "), "more\n");
  refused(redigested(extra), kKey, "a line more");
}

}  // namespace
}  // namespace svbrdf
