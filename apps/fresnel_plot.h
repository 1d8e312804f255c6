#pragma once
// Exact Fresnel reflectance against Schlick's approximation over the angle of incidence
// (CGPP Exercises 27.5, 27.6): the curves, the largest difference and where it falls, and a plot of
// them. Schlick's f0 is the exact reflectance at normal incidence, per channel.
#include <array>
#include <string>
#include <vector>

#include "appearance/bsdf.h"
#include "apps/figure.h"

namespace svbrdf {

struct FresnelCurves {
  std::string label;                      // "ior 1.5" / "eta ..., k ..."
  int channels = 1;                       // 1 for a dielectric, 3 for a conductor
  std::vector<float> theta_deg;           // 0 ... 90
  std::array<std::vector<float>, 3> exact, schlick;
  std::array<float, 3> max_difference{};  // max |exact − schlick| per channel
  std::array<float, 3> max_at_deg{};      // where it falls
};

// `steps` samples of θi over [0°, 90°].
FresnelCurves fresnel_curves_dielectric(float ior, int steps = 9001);
FresnelCurves fresnel_curves_conductor(const Rgb& eta, const Rgb& k, int steps = 9001);
Figure fresnel_plot(const FresnelCurves& c);

}  // namespace svbrdf
