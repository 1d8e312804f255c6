#include "render/crop.h"

#include <cerrno>
#include <cstdlib>
#include <vector>

#include "base/error.h"

namespace svbrdf {

namespace {

// `text` split at `separator` into whole numbers ≥ 0, or an empty list when any part is not one.
std::vector<long long> whole_numbers(const std::string& text, char separator) {
  std::vector<long long> out;
  std::size_t begin = 0;
  while (true) {
    const std::size_t end = text.find(separator, begin);
    const std::string part = text.substr(begin, end == std::string::npos ? std::string::npos : end - begin);
    const char* first = part.c_str();
    char* last = nullptr;
    errno = 0;
    const long long v = std::strtoll(first, &last, 10);
    if (part.empty() || last == first || *last != '\0' || errno == ERANGE || part.find_first_of("+- ") != std::string::npos)
      return {};
    out.push_back(v);
    if (end == std::string::npos) return out;
    begin = end + 1;
  }
}

}  // namespace

PixelRect tile_rect(int index, int count, int width, int height) {
  const auto row = [&](long long i) { return int(i * height / count); };
  return {0, row(index), width, row(index + 1LL)};
}

PixelRect parse_crop(const std::string& text, int width, int height, const std::string& option) {
  const std::string where = option + " " + text;
  const std::vector<long long> v = whole_numbers(text, ',');
  if (v.size() != 4) throw input_error(where, "expected x0,y0,x1,y1: whole pixel numbers, the window [x0, x1) × [y0, y1)");
  if (v[0] >= v[2] || v[1] >= v[3]) throw input_error(where, "the window is empty: x0 < x1 and y0 < y1 are needed");
  if (v[2] > width || v[3] > height)
    throw input_error(where, "the window reaches past the " + std::to_string(width) + "x" + std::to_string(height) + " frame");
  return {int(v[0]), int(v[1]), int(v[2]), int(v[3])};
}

PixelRect parse_tile(const std::string& text, int width, int height, const std::string& option) {
  const std::string where = option + " " + text;
  const std::vector<long long> v = whole_numbers(text, '/');
  if (v.size() != 2) throw input_error(where, "expected I/N: tile I of N, I from 0 to N-1");
  if (v[1] < 1 || v[1] > height)
    throw input_error(where, "N must be from 1 to the frame's " + std::to_string(height) + " rows (a tile is a band of rows)");
  if (v[0] >= v[1]) throw input_error(where, "I must be from 0 to N-1 = " + std::to_string(v[1] - 1));
  return tile_rect(int(v[0]), int(v[1]), width, height);
}

}  // namespace svbrdf
