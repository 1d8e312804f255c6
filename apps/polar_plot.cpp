#include "apps/polar_plot.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "appearance/shading.h"

namespace svbrdf {
namespace {

std::string g(double x) { return plot_number(x); }

}  // namespace

PolarPlotData polar_plot_data(const Bsdf& bsdf, float theta_i_deg, int steps) {
  PolarPlotData d;
  d.theta_i_deg = theta_i_deg;
  const float ti = glm::radians(theta_i_deg);
  d.incident = glm::vec3(-std::sin(ti), 0.0f, std::cos(ti));
  for (int i = 0; i < steps; ++i) {
    const float t = -kPi + kTwoPi * static_cast<float>(i) / static_cast<float>(steps - 1);
    const glm::vec3 w(std::sin(t), 0.0f, std::cos(t));
    d.angles.push_back(t);
    d.bsdf.push_back(luminance(bsdf.eval(d.incident, w)));
    d.density.push_back(bsdf.pdf(w, d.incident));
  }
  d.impulses = bsdf.impulses_out(d.incident);
  return d;
}

Figure polar_plot(const PolarPlotData& d, const std::string& title) {
  // Is there anything below the horizon?
  bool lower = false;
  for (std::size_t i = 0; i < d.angles.size(); ++i)
    if (std::cos(d.angles[i]) < 0 && (d.bsdf[i] > 0 || d.density[i] > 0)) lower = true;
  for (int k = 0; k < d.impulses.count; ++k)
    if (d.impulses.items[static_cast<std::size_t>(k)].direction.z < 0) lower = true;
  float peak = 0;
  for (std::size_t i = 0; i < d.angles.size(); ++i) {
    if (std::isfinite(d.bsdf[i])) peak = std::max(peak, d.bsdf[i]);
    if (std::isfinite(d.density[i])) peak = std::max(peak, d.density[i]);
  }
  const double width = 640, radius = 260, top = 80;
  const double height = top + radius + (lower ? radius + 40 : 60);
  const glm::dvec2 origin(width / 2, top + radius);
  auto at = [&](const glm::vec3& w, double r) { return origin + glm::dvec2(w.x, -w.z) * r; };
  Figure fig(width, height);
  // Scale circles, the surface, the normal.
  for (int c = 1; c <= 4; ++c) fig.circle(origin, radius * c / 4.0, "#dddddd", 1);
  fig.line(origin - glm::dvec2(radius + 20, 0), origin + glm::dvec2(radius + 20, 0), "#888888", 2);
  fig.line(origin, origin - glm::dvec2(0, radius + 10), "#aaaaaa", 1, "4,4");
  auto curve = [&](const std::vector<float>& v, const std::string& color) {
    std::vector<glm::dvec2> pts;
    for (std::size_t i = 0; i < d.angles.size(); ++i) {
      const bool visible = lower || std::cos(d.angles[i]) >= -1e-6f;
      const double r = (peak > 0 && std::isfinite(v[i])) ? radius * v[i] / peak : 0.0;
      if (!visible) {
        fig.polyline(pts, color, 2);
        pts.clear();
        continue;
      }
      pts.push_back(at(glm::vec3(std::sin(d.angles[i]), 0, std::cos(d.angles[i])), r));
    }
    fig.polyline(pts, color, 2);
  };
  curve(d.density, "#1f4fd8");
  curve(d.bsdf, "black");
  // The incoming light: a gray arrow from d toward the surface point.
  fig.arrow(at(d.incident, radius + 15), at(d.incident, 12), "#999999", 2);
  for (int k = 0; k < d.impulses.count; ++k) {
    const Impulse& imp = d.impulses.items[static_cast<std::size_t>(k)];
    const float m = luminance(imp.magnitude);
    fig.arrow(origin, at(imp.direction, radius * std::min(m, 1.05f)), "#c0392b", 3);
    fig.text(at(imp.direction, radius * std::min(m, 1.05f) + 16), g(m), 12, "#c0392b", "middle");
  }
  fig.text({16, 26}, title, 16);
  fig.text({16, 48}, "theta_i = " + g(d.theta_i_deg) + " deg; outer circle = " + g(peak) + " /sr", 13, "#444444");
  fig.text({width - 16, 26}, "f(wi, wo) (luminance)", 13, "black", "end");
  fig.text({width - 16, 44}, "pdf(wi = w | wo = d)", 13, "#1f4fd8", "end");
  fig.text({width - 16, 62}, "impulses (magnitude, 1 = outer circle)", 13, "#c0392b", "end");
  return fig;
}

}  // namespace svbrdf
