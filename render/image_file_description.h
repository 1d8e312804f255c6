#pragma once
// What a texture cache image file (render/texture_tiles.h) says of itself in its description (the
// TIFF ImageDescription): the key it is stored under, the image as the loader decoded it (width,
// height, channels: the file's texels are always RGBA) and which form it holds; for 8-bit codes, the
// tables from code to value of the image and of its linearized copy. A render that finds the file
// takes all it needs of the image from it and decodes nothing (TextureSet::find); lookups return
// what the tables hold, so the tables must come back bit for bit: each float is written as the 8
// hexadecimal digits of its bit pattern, exact for every value (−0, subnormals, NaN payloads), where
// a decimal form would round.
//
// Lines, '\n' after each:
//   svbrdf texture tiles 2
//   key KEY                         (64 hexadecimal digits)
//   image WIDTHxHEIGHTxCHANNELS
//   form codes | form floats
//   raw HEX…                        (codes: 4 × 256 values, channel by channel, code by code)
//   linear HEX…                     (codes of an image a color slot shows)
//   sha256 DIGEST                   (of every byte before this line)
// The digest makes a garbled description one that is refused, not one read as other tables.
#include <optional>
#include <string>
#include <string_view>

#include "render/texture_tiles.h"

namespace svbrdf {

struct ImageFileDescription {
  std::string key;
  int width = 0, height = 0, channels = 0;  // as decoded
  bool codes = false;                       // 8-bit codes with tables; else RGBA floats
  bool linear = false;                      // codes: `linear_table` is there
  CodeTable raw_table{}, linear_table{};
};

std::string describe(const ImageFileDescription& d);

// The description `text` holds when it is one describe() wrote for `key`; nullopt with `why` set
// (what is wrong, for a warning) otherwise.
std::optional<ImageFileDescription> parse_image_file_description(std::string_view text, const std::string& key,
                                                                 std::string* why);

}  // namespace svbrdf
