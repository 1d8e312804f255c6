#include "apps/svg.h"

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

std::string stroke(const std::string& color, double width, const std::string& dash) {
  std::string s = " fill=\"none\" stroke=\"" + color + "\" stroke-width=\"" + num(width) + "\"";
  if (!dash.empty()) s += " stroke-dasharray=\"" + dash + "\"";
  return s;
}

}  // namespace

Svg::Svg(double width, double height) : width_(width), height_(height) {}

void Svg::line(glm::dvec2 a, glm::dvec2 b, const std::string& color, double width, const std::string& dash) {
  body_ += "<line x1=\"" + num(a.x) + "\" y1=\"" + num(a.y) + "\" x2=\"" + num(b.x) + "\" y2=\"" + num(b.y) + "\"" +
           stroke(color, width, dash) + "/>\n";
}

void Svg::polyline(const std::vector<glm::dvec2>& points, const std::string& color, double width, const std::string& dash) {
  if (points.size() < 2) return;
  body_ += "<polyline points=\"";
  for (const glm::dvec2& p : points) {
    body_ += num(p.x);
    body_ += ',';
    body_ += num(p.y);
    body_ += ' ';
  }
  body_ += '"';
  body_ += stroke(color, width, dash);
  body_ += " stroke-linejoin=\"round\"/>\n";
}

void Svg::circle(glm::dvec2 c, double r, const std::string& color, double width, const std::string& dash) {
  body_ += "<circle cx=\"" + num(c.x) + "\" cy=\"" + num(c.y) + "\" r=\"" + num(r) + "\"" + stroke(color, width, dash) + "/>\n";
}

void Svg::arrow(glm::dvec2 a, glm::dvec2 b, const std::string& color, double width) {
  const glm::dvec2 d = b - a;
  const double len = glm::length(d);
  if (len < 1e-9) return;
  const glm::dvec2 u = d / len, n(-u.y, u.x);
  const double head = std::min(12.0, 0.4 * len);
  const glm::dvec2 base = b - u * head;
  line(a, base, color, width);
  const glm::dvec2 p1 = base + n * (head * 0.4), p2 = base - n * (head * 0.4);
  body_ += "<polygon points=\"" + num(b.x) + "," + num(b.y) + " " + num(p1.x) + "," + num(p1.y) + " " + num(p2.x) +
           "," + num(p2.y) + "\" fill=\"" + color + "\"/>\n";
}

void Svg::text(glm::dvec2 at, const std::string& s, double size, const std::string& color, const std::string& anchor) {
  body_ += "<text x=\"" + num(at.x) + "\" y=\"" + num(at.y) + "\" font-family=\"sans-serif\" font-size=\"" + num(size) +
           "\" fill=\"" + color + "\" text-anchor=\"" + anchor + "\">" + markup_escape(s) + "</text>\n";
}

std::string Svg::str() const {
  return "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<svg xmlns=\"http://www.w3.org/2000/svg\" version=\"1.1\" width=\"" +
         num(width_) + "\" height=\"" + num(height_) + "\" viewBox=\"0 0 " + num(width_) + " " + num(height_) +
         "\">\n<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n" + body_ + "</svg>\n";
}

void Svg::write(const std::filesystem::path& path) const {
  const std::string doc = str();
  write_bytes_atomically(path, std::as_bytes(std::span(doc)));
}

}  // namespace svbrdf
