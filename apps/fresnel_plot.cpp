#include "apps/fresnel_plot.h"

#include <cmath>
#include <cstdio>

#include "appearance/fresnel.h"

namespace svbrdf {
namespace {

std::string g(double x) { return plot_number(x); }

template <class Exact>
FresnelCurves curves(int channels, int steps, const Exact& exact) {
  FresnelCurves c;
  c.channels = channels;
  for (int ch = 0; ch < channels; ++ch) {
    const float f0 = exact(ch, 1.0f);
    for (int i = 0; i < steps; ++i) {
      const float deg = 90.0f * static_cast<float>(i) / static_cast<float>(steps - 1);
      const float cos_i = std::cos(glm::radians(deg));
      if (ch == 0) c.theta_deg.push_back(deg);
      const float e = exact(ch, cos_i), s = fresnel_schlick(f0, cos_i);
      c.exact[static_cast<std::size_t>(ch)].push_back(e);
      c.schlick[static_cast<std::size_t>(ch)].push_back(s);
      if (std::abs(e - s) > c.max_difference[static_cast<std::size_t>(ch)]) {
        c.max_difference[static_cast<std::size_t>(ch)] = std::abs(e - s);
        c.max_at_deg[static_cast<std::size_t>(ch)] = deg;
      }
    }
  }
  return c;
}

}  // namespace

FresnelCurves fresnel_curves_dielectric(float ior, int steps) {
  FresnelCurves c = curves(1, steps, [&](int, float cos_i) { return fresnel_dielectric(cos_i, ior); });
  c.label = "dielectric, ior " + g(ior);
  return c;
}

FresnelCurves fresnel_curves_conductor(const Rgb& eta, const Rgb& k, int steps) {
  FresnelCurves c = curves(3, steps, [&](int ch, float cos_i) { return fresnel_conductor(cos_i, eta[ch], k[ch]); });
  c.label = "conductor, eta " + g(eta.x) + "," + g(eta.y) + "," + g(eta.z) + ", k " + g(k.x) + "," + g(k.y) + "," + g(k.z);
  return c;
}

Figure fresnel_plot(const FresnelCurves& c) {
  // The heading stacks its parts a line each (the title, the material, each channel's largest
  // difference in its curve's colour), so that no line outgrows the frame: a conductor's three
  // summaries on one line are twice as wide as the plot.
  const double line = 18, heading = 24 + line * (1 + c.channels);
  const double left = 70, top = heading + 16, w = 540, h = 360;
  Figure fig(left + w + 30, top + h + 60);
  auto at = [&](double deg, double r) { return glm::dvec2(left + w * deg / 90.0, top + h * (1.0 - r)); };
  for (int i = 0; i <= 9; ++i) {
    fig.line(at(10.0 * i, 0), at(10.0 * i, 1), "#e4e4e4", 1);
    fig.text(at(10.0 * i, 0) + glm::dvec2(0, 18), g(10.0 * i), 12, "#444444", "middle");
  }
  for (int i = 0; i <= 10; ++i) {
    fig.line(at(0, 0.1 * i), at(90, 0.1 * i), "#e4e4e4", 1);
    fig.text(at(0, 0.1 * i) + glm::dvec2(-8, 4), g(0.1 * i), 12, "#444444", "end");
  }
  fig.line(at(0, 0), at(90, 0), "black", 1.5);
  fig.line(at(0, 0), at(0, 1), "black", 1.5);
  const char* colors3[] = {"#d62728", "#2ca02c", "#1f4fd8"};
  fig.text({left, 24}, "Fresnel reflectance: exact (solid) vs Schlick (dashed)", 15);
  fig.text({left, 24 + line}, c.label, 12, "#444444");
  for (int ch = 0; ch < c.channels; ++ch) {
    const auto i = static_cast<std::size_t>(ch);
    const std::string color = c.channels == 1 ? "black" : colors3[i];
    std::vector<glm::dvec2> e, s;
    for (std::size_t j = 0; j < c.theta_deg.size(); ++j) {
      e.push_back(at(c.theta_deg[j], c.exact[i][j]));
      s.push_back(at(c.theta_deg[j], c.schlick[i][j]));
    }
    fig.polyline(e, color, 2);
    fig.polyline(s, color, 2, "7,5");
    const double md = c.max_difference[i], ma = c.max_at_deg[i];
    fig.line(at(ma, 0), at(ma, 1), color, 0.8, "2,3");
    const std::string channel = c.channels == 3 ? std::string("RGB").substr(i, 1) + ": " : "";
    fig.text({left, 24 + line * (2 + ch)}, channel + "max |exact - Schlick| " + g(md) + " at " + g(ma) + " deg", 12,
             c.channels == 1 ? "#444444" : color);
  }
  fig.text({left + w / 2, top + h + 44}, "angle of incidence (degrees)", 13, "black", "middle");
  return fig;
}

}  // namespace svbrdf
