#pragma once
// The polar plot of CGPP Figures 27.7/27.9 for one model: a fixed direction d at θi in the plane of
// incidence (the xz plane, light arriving from the −x side), and, over directions w(t) = (sin t, 0,
// cos t) of that plane,
//   black: f(d, w) (luminance of the RGB value, Rec. 709 weights),
//   blue:  pdf(w, d), the density with which sample(wo = d) chooses wi = w (same unit, 1/sr,
//          drawn to the same radial scale),
//   arrows: the impulses of impulses_out(d), length = luminance of the magnitude × the radius
//          that stands for 1 (impulses carry no 1/sr; capped at 1.05, the value is written at the
//          tip), and a gray arrow for the incoming light.
// The lower half is drawn only when something (a refraction, a value) lies there.
#include <string>
#include <vector>

#include "appearance/bsdf.h"
#include "apps/figure.h"

namespace svbrdf {

struct PolarPlotData {
  float theta_i_deg = 0;
  glm::vec3 incident{0, 0, 1};  // d
  std::vector<float> angles;    // t in radians, from −π to π, 0 = the normal, positive toward +x
  std::vector<float> bsdf;      // luminance of f(d, w(t))
  std::vector<float> density;   // pdf(w(t), d)
  Impulses impulses;            // impulses_out(d)
};

inline float luminance(const Rgb& c) { return 0.2126f * c.x + 0.7152f * c.y + 0.0722f * c.z; }

PolarPlotData polar_plot_data(const Bsdf& bsdf, float theta_i_deg, int steps = 1441);
Figure polar_plot(const PolarPlotData& data, const std::string& title);

}  // namespace svbrdf
