// Figure::raster: the plot's shapes drawn into pixels as an SVG renderer draws them. Each shape's
// coverage of every pixel (the area of the pixel it covers, antialiased by distance for strokes and
// by 4×4 subsamples for fills) is gathered first, so overlapping segments of one polyline do not darken
// their joints, then the shape's color is blended over what is there by that coverage, in order. The
// blend is done on the encoded sRGB values, as browsers blend SVG. Text is OpenImageIO's
// (ImageBufAlgo::render_text, FreeType).
#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <numbers>

#include "apps/figure.h"
#include "base/error.h"

namespace svbrdf {

namespace {

using Color = std::array<float, 3>;
using Points = std::vector<glm::dvec2>;

// The font the PNG's text is drawn with: DejaVu Sans, Debian's default sans-serif (fonts-dejavu-core).
constexpr const char* kFont = "DejaVuSans";

Color parse_color(const std::string& text) {
  if (text == "black") return {0, 0, 0};
  if (text == "white") return {1, 1, 1};
  if (text.size() == 7 && text[0] == '#') {
    Color c{};
    for (int i = 0; i < 3; ++i) {
      char* end = nullptr;
      const std::string part = text.substr(1 + 2 * std::size_t(i), 2);
      const long v = std::strtol(part.c_str(), &end, 16);
      if (*end != '\0') break;
      c[std::size_t(i)] = float(v) / 255.0f;
      if (i == 2) return c;
    }
  }
  throw Error("a plot color \"" + text + "\" that the PNG writer does not know", Error::Kind::internal);
}

// SVG's stroke-dasharray: lengths separated by commas or spaces; an odd list repeats to be even.
std::vector<double> parse_dash(const std::string& text) {
  std::vector<double> dash;
  const char* p = text.c_str();
  while (*p) {
    char* end = nullptr;
    const double v = std::strtod(p, &end);
    if (end == p) {
      ++p;
      continue;
    }
    if (v > 0) dash.push_back(v);
    p = end;
  }
  if (dash.size() % 2) dash.insert(dash.end(), dash.begin(), dash.end());
  return dash;
}

// The parts of a polyline that a dash pattern draws, each a polyline of its own.
std::vector<Points> dashed(const Points& line, const std::vector<double>& dash) {
  if (dash.empty()) return {line};
  std::vector<Points> parts;
  std::size_t k = 0;            // the dash entry we are in: even on, odd off
  double left = dash[0];        // what remains of it
  Points current = {line[0]};
  for (std::size_t i = 0; i + 1 < line.size(); ++i) {
    glm::dvec2 a = line[i];
    const glm::dvec2 b = line[i + 1];
    double rest = glm::length(b - a);
    while (rest > left) {
      a += (b - a) * (left / rest);
      rest -= left;
      if (k % 2 == 0) {
        current.push_back(a);
        parts.push_back(std::move(current));
      }
      current = {a};
      k = (k + 1) % dash.size();
      left = dash[k];
    }
    left -= rest;
    current.push_back(b);
  }
  if (k % 2 == 0 && current.size() > 1) parts.push_back(std::move(current));
  return parts;
}

double distance_to_segment(glm::dvec2 p, glm::dvec2 a, glm::dvec2 b) {
  const glm::dvec2 ab = b - a;
  const double len2 = glm::dot(ab, ab);
  const double t = len2 > 0 ? std::clamp(glm::dot(p - a, ab) / len2, 0.0, 1.0) : 0.0;
  return glm::length(p - (a + t * ab));
}

bool inside(glm::dvec2 p, const Points& polygon) {  // even-odd rule
  bool in = false;
  for (std::size_t i = 0, j = polygon.size() - 1; i < polygon.size(); j = i++) {
    const glm::dvec2 a = polygon[i], b = polygon[j];
    if ((a.y > p.y) != (b.y > p.y) && p.x < a.x + (p.y - a.y) * (b.x - a.x) / (b.y - a.y)) in = !in;
  }
  return in;
}

class Canvas {
 public:
  Canvas(int width, int height)
      : width_(width), height_(height), image_(width, height, 3), cover_(std::size_t(width) * height, 0.0f) {
    std::fill(image_.pixels.begin(), image_.pixels.end(), 1.0f);
  }

  void stroke(const Points& line, double width) {
    // A stroke thinner than a pixel covers less of it: its peak coverage is its width.
    const double peak = std::min(width, 1.0), half = 0.5 * std::max(width, 1.0);
    for (std::size_t i = 0; i + 1 < line.size(); ++i) {
      const glm::dvec2 a = line[i], b = line[i + 1];
      for_pixels(glm::min(a, b) - (half + 1), glm::max(a, b) + (half + 1), [&](glm::dvec2 p, float& c) {
        const double d = distance_to_segment(p, a, b);
        c = std::max(c, float(peak * std::clamp(half + 0.5 - d, 0.0, 1.0)));
      });
    }
  }

  void fill(const Points& polygon) {
    glm::dvec2 lo = polygon[0], hi = polygon[0];
    for (const glm::dvec2& q : polygon) lo = glm::min(lo, q), hi = glm::max(hi, q);
    for_pixels(lo, hi, [&](glm::dvec2 p, float& c) {
      int n = 0;
      for (int sy = 0; sy < 4; ++sy)
        for (int sx = 0; sx < 4; ++sx) n += inside(p + glm::dvec2((sx - 1.5) / 4, (sy - 1.5) / 4), polygon);
      c = std::max(c, n / 16.0f);
    });
  }

  // Blends `color` over the image by the coverage gathered since the last call, and clears it.
  void paint(const Color& color) {
    for (int y = dirty_lo_.y; y < dirty_hi_.y; ++y)
      for (int x = dirty_lo_.x; x < dirty_hi_.x; ++x) {
        float& c = cover_[std::size_t(y) * width_ + x];
        for (int k = 0; k < 3; ++k) image_.at(x, y, k) += (color[std::size_t(k)] - image_.at(x, y, k)) * c;
        c = 0.0f;
      }
    dirty_lo_ = {width_, height_}, dirty_hi_ = {0, 0};
  }

  void text(const Figure::Shape& s, const Color& color) {
    OIIO::ImageBuf buf(OIIO::ImageSpec(width_, height_, 3, OIIO::TypeDesc::FLOAT), image_.pixels.data());
    const OIIO::ImageBufAlgo::TextAlignX align = s.anchor == "middle" ? OIIO::ImageBufAlgo::TextAlignX::Center
                                                 : s.anchor == "end"  ? OIIO::ImageBufAlgo::TextAlignX::Right
                                                                      : OIIO::ImageBufAlgo::TextAlignX::Left;
    if (!OIIO::ImageBufAlgo::render_text(buf, int(std::lround(s.points[0].x)), int(std::lround(s.points[0].y)), s.text,
                                         int(std::lround(s.size)), kFont, color, align))
      throw Error("cannot draw the plot's text: OpenImageIO found no DejaVu Sans font (" + buf.geterror() +
                      "; Debian's package fonts-dejavu-core has it)",
                  Error::Kind::environment);
  }

  Image take() { return std::move(image_); }

 private:
  // Calls f(pixel center, coverage) for every pixel of the box [lo, hi] inside the image.
  template <class F>
  void for_pixels(glm::dvec2 lo, glm::dvec2 hi, F&& f) {
    const int x0 = std::max(0, int(std::floor(lo.x))), y0 = std::max(0, int(std::floor(lo.y)));
    const int x1 = std::min(width_, int(std::ceil(hi.x)) + 1), y1 = std::min(height_, int(std::ceil(hi.y)) + 1);
    if (x0 >= x1 || y0 >= y1) return;
    dirty_lo_ = glm::min(dirty_lo_, glm::ivec2(x0, y0)), dirty_hi_ = glm::max(dirty_hi_, glm::ivec2(x1, y1));
    for (int y = y0; y < y1; ++y)
      for (int x = x0; x < x1; ++x) f(glm::dvec2(x + 0.5, y + 0.5), cover_[std::size_t(y) * width_ + x]);
  }

  int width_, height_;
  Image image_;
  std::vector<float> cover_;
  glm::ivec2 dirty_lo_{width_, height_}, dirty_hi_{0, 0};
};

// A circle as the polyline of its perimeter, segments of about 2 units.
Points circle_points(glm::dvec2 c, double r) {
  const int n = std::max(32, int(std::ceil(2 * std::numbers::pi * r / 2)));
  Points p;
  for (int i = 0; i <= n; ++i) {
    const double t = 2 * std::numbers::pi * i / n;
    p.push_back(c + r * glm::dvec2(std::cos(t), std::sin(t)));
  }
  return p;
}

}  // namespace

std::pair<glm::dvec2, glm::dvec2> Figure::text_box(const Shape& s) {
  // text_size is relative to the left end of the baseline; render_text's alignment moves it left by
  // its whole (end) or half (middle) width, as raster() draws it.
  const OIIO::ROI r = OIIO::ImageBufAlgo::text_size(s.text, int(std::lround(s.size)), kFont);
  if (!r.defined())
    throw Error("cannot measure the plot's text: OpenImageIO found no DejaVu Sans font (Debian's package "
                "fonts-dejavu-core has it)",
                Error::Kind::environment);
  const double w = r.xend - r.xbegin, shift = s.anchor == "middle" ? 0.5 * w : s.anchor == "end" ? w : 0.0;
  const glm::dvec2 at(std::lround(s.points[0].x), std::lround(s.points[0].y));
  return {at + glm::dvec2(r.xbegin - shift, r.ybegin), at + glm::dvec2(r.xend - shift, r.yend)};
}

Image Figure::raster() const {
  Canvas canvas(int(std::ceil(width_)), int(std::ceil(height_)));
  for (const Shape& s : shapes_) {
    const Color color = parse_color(s.color);
    switch (s.kind) {
      case Shape::Kind::line:
      case Shape::Kind::polyline:
      case Shape::Kind::circle:
        for (const Points& part : dashed(s.kind == Shape::Kind::circle ? circle_points(s.points[0], s.radius) : s.points,
                                         parse_dash(s.dash)))
          canvas.stroke(part, s.width);
        canvas.paint(color);
        break;
      case Shape::Kind::polygon:
        canvas.fill(s.points);
        canvas.paint(color);
        break;
      case Shape::Kind::text:
        canvas.text(s, color);
        break;
    }
  }
  return canvas.take();
}

}  // namespace svbrdf
