// Printed paper: white paper with black ink, the control case of the MIP tests — only the albedo
// varies; roughness and metallic are constant and the surface is flat, so averaging parameters and
// averaging BRDFs must agree (the BRDF is linear in base color at fixed roughness, metallic and
// normal). Variants: `text` (lines of text-like glyphs: stems, bowls, bars, diagonals at a 2 mm
// x-height) and `halftone` (a continuous-tone picture screened with round dots at 45°, ~50 lpi).
// Ink coverage per texel is the area fraction, estimated with 4×4 samples.
#include <string>
#include <vector>

#include "base/error.h"
#include "textures/families.h"
#include "textures/noise.h"
#include "base/math.h"

namespace svbrdf::family {

namespace {

const glm::vec3 kPaper = srgb8(240, 238, 231);
const glm::vec3 kInk = srgb8(40, 40, 44);
constexpr float kPaperRoughness = 0.6f;  // 153/255: stored exactly in 8 bits
constexpr int kSamples = 4;              // per axis, per texel

// ---- text ----
constexpr double kLinePitchMm = 4.5;
constexpr double kCharPitchMm = 1.5;
constexpr double kXHeightMm = 1.6, kAscenderMm = 2.3, kDescenderMm = 0.6;
constexpr double kGlyphWidthMm = 1.1;
constexpr double kStrokeMm = 0.22;

double segment_distance(glm::dvec2 p, glm::dvec2 a, glm::dvec2 b) {
  const glm::dvec2 ab = b - a;
  const double t = glm::clamp(glm::dot(p - a, ab) / glm::dot(ab, ab), 0.0, 1.0);
  return glm::length(p - (a + t * ab));
}

// Is the point p (mm, glyph box coordinates: x right from the glyph's left edge, y up from the
// baseline) inked by glyph `code`? A glyph is 1–3 strokes chosen by the code's bits.
bool glyph_ink(std::uint64_t code, glm::dvec2 p) {
  const double w = kGlyphWidthMm, x = kXHeightMm, half = 0.5 * kStrokeMm;
  const int shape = int(code % 7);
  const bool ascender = (code >> 4) % 5 == 0, descender = (code >> 8) % 7 == 0, bar = (code >> 12) % 3 == 0;
  double dist = 1e9;
  const auto seg = [&](glm::dvec2 a, glm::dvec2 b) { dist = std::min(dist, segment_distance(p, a, b)); };
  switch (shape) {
    case 0:  // o
    case 1: {  // o with a stem (a, b, d, p, q)
      const glm::dvec2 c(0.5 * w, 0.5 * x);
      const glm::dvec2 q = (p - c) / glm::dvec2(0.5 * w - half, 0.5 * x - half);
      dist = std::abs(glm::length(q) - 1.0) * std::min(0.5 * w, 0.5 * x);
      if (shape == 1) seg({(code >> 16) % 2 ? w - half : half, ascender ? kAscenderMm : x}, {(code >> 16) % 2 ? w - half : half, descender ? -kDescenderMm : 0.0});
      break;
    }
    case 2:  // n, h, u
      seg({half, ascender ? kAscenderMm : x}, {half, 0});
      seg({w - half, x * 0.75}, {w - half, 0});
      seg({half, x * 0.75}, {0.5 * w, x - half});
      seg({0.5 * w, x - half}, {w - half, x * 0.75});
      break;
    case 3:  // l, i, t
      seg({0.5 * w, ascender ? kAscenderMm : x}, {0.5 * w, descender ? -kDescenderMm : 0.0});
      if (bar) seg({0.15 * w, x}, {0.85 * w, x});
      break;
    case 4:  // v, x, k
      seg({half, x}, {0.5 * w, 0});
      seg({0.5 * w, 0}, {w - half, x});
      if (bar) seg({half, 0}, {w - half, x});
      break;
    case 5:  // e, s, z
      seg({half, x - half}, {w - half, x - half});
      seg({half, 0.5 * x}, {w - half, 0.5 * x});
      seg({half, half}, {w - half, half});
      seg((code >> 20) % 2 ? glm::dvec2(half, x - half) : glm::dvec2(w - half, x - half),
          (code >> 20) % 2 ? glm::dvec2(w - half, half) : glm::dvec2(half, half));
      break;
    default:  // r, c, f
      seg({half, descender ? -kDescenderMm : 0.0}, {half, ascender ? kAscenderMm : x});
      seg({half, x - half}, {w - half, x - half});
      break;
  }
  return dist <= half;
}

// Text layout over the periodic page: `lines` lines of `chars` character cells; words of 2–9
// letters separated by one space; one line in six ends early (a paragraph end).
struct TextLayout {
  int lines, chars;
  double line_pitch, char_pitch;
  std::uint64_t seed;
  std::vector<unsigned char> inked_cell;  // lines × chars: 1 where a glyph stands, 0 for a space

  TextLayout(int lines_, int chars_, double side, std::uint64_t seed_)
      : lines(lines_), chars(chars_), line_pitch(side / lines_), char_pitch(side / chars_), seed(seed_),
        inked_cell(std::size_t(lines_) * chars_, 0) {
    for (int l = 0; l < lines; ++l) {
      const bool short_line = noise::unit(seed, l, 0, 1) < 1.0f / 6.0f;
      const int end = short_line ? int(chars * (0.3f + 0.6f * noise::unit(seed, l, 0, 2))) : chars;
      int c = 0;
      for (int w = 0; c < end; ++w) {
        const int len = 2 + int(noise::unit(seed, l, w, 3) * 8.0f);
        for (int k = 0; k < len && c < end; ++k) inked_cell[std::size_t(l) * chars + c++] = 1;
        ++c;  // the space after the word
      }
    }
  }

  bool ink(double x_mm, double y_mm) const {
    const int line = int(std::floor(y_mm / line_pitch)), cell = int(std::floor(x_mm / char_pitch));
    const int l = ((line % lines) + lines) % lines, c = ((cell % chars) + chars) % chars;
    if (!inked_cell[std::size_t(l) * chars + c]) return false;
    const glm::dvec2 p(x_mm - cell * char_pitch - 0.5 * (char_pitch - kGlyphWidthMm),
                       (line + 1) * line_pitch - 1.3 * kDescenderMm - y_mm);  // y up from the baseline
    return glyph_ink(noise::hash(seed, l, c, 4), p);
  }
};

// ---- halftone ----
constexpr double kScreenPitchMm = 0.5;   // dot spacing: about 50 lines per inch
constexpr double kPictureFeatureMm = 8.0;

struct Halftone {
  double side, pitch;
  int picture_cells;
  std::uint64_t seed;

  bool ink(double x_mm, double y_mm) const {
    // Tone (ink fraction) of the continuous picture at this point.
    const float tone = glm::clamp(0.5f + 0.55f * noise::fbm(seed, x_mm / side, y_mm / side, picture_cells, 3), 0.02f, 0.98f);
    // Screen coordinates: the grid turned 45°; one cell is pitch × pitch.
    const double a = (x_mm + y_mm) / (pitch * std::sqrt(2.0)), b = (y_mm - x_mm) / (pitch * std::sqrt(2.0));
    const double fa = a - std::floor(a) - 0.5, fb = b - std::floor(b) - 0.5;  // from the cell center
    if (tone <= 0.5f) return fa * fa + fb * fb <= tone / kPiD;  // a round dot of area `tone`
    const double ca = 0.5 - std::abs(fa), cb = 0.5 - std::abs(fb);          // from the nearest corner
    return ca * ca + cb * cb > (1.0 - tone) / kPiD;             // round holes of area 1 − tone
  }
};

}  // namespace

void printed_paper(const Domain& d, std::string_view variant, std::uint64_t seed, Canvas& out) {
  const double side = d.side_mm();
  const bool text = variant == "text";
  if (!text && variant != "halftone") throw Error("printed-paper: unknown variant \"" + std::string(variant) + "\"");
  const int lines = noise::cells_for(side, kLinePitchMm), chars = noise::cells_for(side, kCharPitchMm);
  const TextLayout layout(text ? lines : 1, text ? chars : 1, side, noise::hash(seed, 21));
  // The 45° screen tiles when the texture side is a whole number of its horizontal period pitch·√2.
  const int screen_periods = noise::cells_for(side, kScreenPitchMm * std::sqrt(2.0));
  const Halftone screen{side, side / screen_periods / std::sqrt(2.0), noise::cells_for(side, kPictureFeatureMm),
                        noise::hash(seed, 22)};
  MaterialTexels& t = out.texels;
  for_each_row(d.size, [&](int j) {
    for (int i = 0; i < d.size; ++i) {
      int inked = 0;
      for (int sy = 0; sy < kSamples; ++sy)
        for (int sx = 0; sx < kSamples; ++sx) {
          const double x = (i + (sx + 0.5) / kSamples) * d.mm_per_texel, y = (j + (sy + 0.5) / kSamples) * d.mm_per_texel;
          inked += (text ? layout.ink(x, y) : screen.ink(x, y)) ? 1 : 0;
        }
      const float coverage = float(inked) / float(kSamples * kSamples);
      const std::size_t k = t.index(i, j);
      t.base_color[k] = glm::mix(kPaper, kInk, coverage);
      t.roughness[k] = kPaperRoughness;
      t.metallic[k] = 0.0f;
      out.height_mm[k] = 0.0f;
    }
  });
}

}  // namespace svbrdf::family
