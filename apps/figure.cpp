#include "apps/figure.h"

#include <cmath>
#include <cstdio>
#include <span>

#include "base/atomic_file.h"
#include "base/error.h"
#include "base/markup_escape.h"

namespace svbrdf {

std::string plot_number(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.4g", x);
  return buf;
}
namespace {

std::string num(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.2f", std::isfinite(x) ? x : 0.0);
  return buf;
}

std::string stroke(const Figure::Shape& s) {
  std::string out = " fill=\"none\" stroke=\"" + s.color + "\" stroke-width=\"" + num(s.width) + "\"";
  if (!s.dash.empty()) out += " stroke-dasharray=\"" + s.dash + "\"";
  return out;
}

std::string svg_element(const Figure::Shape& s) {
  using Kind = Figure::Shape::Kind;
  const std::vector<glm::dvec2>& p = s.points;
  switch (s.kind) {
    case Kind::line:
      return "<line x1=\"" + num(p[0].x) + "\" y1=\"" + num(p[0].y) + "\" x2=\"" + num(p[1].x) + "\" y2=\"" + num(p[1].y) +
             "\"" + stroke(s) + "/>\n";
    case Kind::polyline: {
      std::string out = "<polyline points=\"";
      for (const glm::dvec2& q : p) {
        out += num(q.x);
        out += ',';
        out += num(q.y);
        out += ' ';
      }
      return out + "\"" + stroke(s) + " stroke-linejoin=\"round\"/>\n";
    }
    case Kind::circle:
      return "<circle cx=\"" + num(p[0].x) + "\" cy=\"" + num(p[0].y) + "\" r=\"" + num(s.radius) + "\"" + stroke(s) + "/>\n";
    case Kind::polygon: {
      std::string points;
      for (const glm::dvec2& q : p) {
        if (!points.empty()) points += ' ';
        points += num(q.x);
        points += ',';
        points += num(q.y);
      }
      return "<polygon points=\"" + points + "\" fill=\"" + s.color + "\"/>\n";
    }
    case Kind::text:
      return "<text x=\"" + num(p[0].x) + "\" y=\"" + num(p[0].y) + "\" font-family=\"sans-serif\" font-size=\"" +
             num(s.size) + "\" fill=\"" + s.color + "\" text-anchor=\"" + s.anchor + "\">" + markup_escape(s.text) +
             "</text>\n";
  }
  return {};
}

Figure::Shape shape(Figure::Shape::Kind kind, std::vector<glm::dvec2> points, const std::string& color, double width = 1,
                    const std::string& dash = "") {
  Figure::Shape s;
  s.kind = kind;
  s.points = std::move(points);
  s.color = color;
  s.width = width;
  s.dash = dash;
  return s;
}

}  // namespace

Figure::Figure(double width, double height) : width_(width), height_(height) {}

void Figure::line(glm::dvec2 a, glm::dvec2 b, const std::string& color, double width, const std::string& dash) {
  shapes_.push_back(shape(Shape::Kind::line, {a, b}, color, width, dash));
}

void Figure::polyline(const std::vector<glm::dvec2>& points, const std::string& color, double width,
                      const std::string& dash) {
  if (points.size() < 2) return;
  shapes_.push_back(shape(Shape::Kind::polyline, points, color, width, dash));
}

void Figure::circle(glm::dvec2 c, double r, const std::string& color, double width, const std::string& dash) {
  Shape s = shape(Shape::Kind::circle, {c}, color, width, dash);
  s.radius = r;
  shapes_.push_back(std::move(s));
}

void Figure::arrow(glm::dvec2 a, glm::dvec2 b, const std::string& color, double width) {
  const glm::dvec2 d = b - a;
  const double len = glm::length(d);
  if (len < 1e-9) return;
  const glm::dvec2 u = d / len, n(-u.y, u.x);
  const double head = std::min(12.0, 0.4 * len);
  const glm::dvec2 base = b - u * head;
  line(a, base, color, width);
  shapes_.push_back(shape(Shape::Kind::polygon, {b, base + n * (head * 0.4), base - n * (head * 0.4)}, color));
}

void Figure::text(glm::dvec2 at, const std::string& s, double size, const std::string& color, const std::string& anchor) {
  Shape t = shape(Shape::Kind::text, {at}, color);
  t.text = s;
  t.size = size;
  t.anchor = anchor;
  shapes_.push_back(std::move(t));
}

std::string Figure::svg() const {
  std::string body;
  for (const Shape& s : shapes_) body += svg_element(s);
  return "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<svg xmlns=\"http://www.w3.org/2000/svg\" version=\"1.1\" width=\"" +
         num(width_) + "\" height=\"" + num(height_) + "\" viewBox=\"0 0 " + num(width_) + " " + num(height_) +
         "\">\n<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n" + body + "</svg>\n";
}

void Figure::write(const std::filesystem::path& path) const {
  const std::string ext = path.extension().string();
  if (ext == ".svg") {
    const std::string doc = svg();
    write_bytes_atomically(path, std::as_bytes(std::span(doc)));
  } else if (ext == ".png") {
    write_image(path, raster(), PixelFormat::uint8);
  } else {
    throw input_error(path.string(), "a plot is written as .svg or .png");
  }
}

}  // namespace svbrdf
