#include "mip/albedo_table.h"

#include <cmath>

#include "appearance/microfacet_core.h"
#include "base/math.h"
#include "mip/reduction_numerics.h"

namespace svbrdf::reduction {

const SpecAlbedoTable& SpecAlbedoTable::get() {
  static const SpecAlbedoTable t;
  return t;
}

SpecAlbedoTable::SpecAlbedoTable() {
  constexpr int n = 64;
  for (int k = 0; k < kSize; ++k) {
    const double a2 = std::exp(std::log(kMin) * (1.0 - double(k) / (kSize - 1)));
    double sa = 0, sb = 0, sba = 0, sbb = 0;
    for (double theta : {0.0, 45.0, 75.0}) {
      const glm::dvec3 wi(std::sin(radians_of(theta)), 0, std::cos(radians_of(theta)));
      for (int p = 0; p < n; ++p)
        for (int q = 0; q < n; ++q) {
          // h with density D(h)·cosθh: tan²θh = α²·u/(1 − u) (Walter et al. 2007); then
          // f·wo.z/pdf(wo) with pdf(wo) = D·cosθh/(4·wo·h), so D cancels.
          // Beckmann: tan²θh = −α²·ln(1 − u) (Walter et al. 2007, eq. 28).
          const double u = (p + 0.5) / n, phi = 2 * kPiD * (q + 0.5) / n;
          for (int beckmann = 0; beckmann < 2; ++beckmann) {
            const double tan2 = beckmann ? -a2 * std::log1p(-u) : a2 * u / (1 - u);
            const double c = 1 / std::sqrt(1 + tan2), sn = std::sqrt(std::max(0.0, 1 - c * c));
            const glm::dvec3 h(sn * std::cos(phi), sn * std::sin(phi), c);
            const double oh = glm::dot(wi, h);
            const glm::dvec3 wo = 2 * oh * h - wi;
            if (wo.z <= 0 || oh <= 0) continue;
            const double vis = smith_ggx_visibility(a2, wi.z, wo.z), w = schlick_weight(oh);
            const double g = 4 * vis * wo.z * oh / c;
            (beckmann ? sba : sa) += g;      // F0 = 1: F = 1
            (beckmann ? sbb : sb) += g * w;  // F0 = 0: F = w
          }
        }
    }
    a_[static_cast<std::size_t>(k)] = sa / (n * n);
    b_[static_cast<std::size_t>(k)] = sb / (n * n);
    ba_[static_cast<std::size_t>(k)] = sba / (n * n);
    bb_[static_cast<std::size_t>(k)] = sbb / (n * n);
  }
}

namespace {
// A stretched lobe (lobe.h) reflects about what the isotropic one of α² times the power mean
// M_0.9(r, 1/r) = ((r^0.9 + r^−0.9)/2)^(1/0.9) reflects: within 0.6 % over perceptual roughness
// 0.05–0.8 and anisotropy strengths 0.3–1 (r up to 400), θi 0°, 45°, 75° and the incident azimuths,
// against the quadrature of the stretched lobe (anisotropy_pyramid_test.cpp). The geometric mean
// (α² itself) overestimates it by up to 68 % (the wide axis's masking loses what the narrow one
// keeps), the arithmetic mean (M_1) underestimates it by up to 3.3 %, M_0.8 overestimates by 3.5 %.
double stretch_albedo_factor(double r) { return std::pow(0.5 * (std::pow(r, 0.9) + std::pow(r, -0.9)), 1.0 / 0.9); }
}  // namespace

double transmission_flux(const Lobe& lobe) {
  if (!transmits(lobe)) return 0.0;
  const SpecAlbedoTable& t = SpecAlbedoTable::get();
  const bool own = lobe.transmission_alpha2 > 0.0f;  // its own shape (lobe.h transmission_shape)
  const float r = own ? lobe.transmission_stretch : lobe.stretch;
  const double k = r > 1.0f ? stretch_albedo_factor(r) : 1.0;
  const double lo = double(own ? lobe.transmission_alpha2 : lobe.alpha2) * k;
  const double f0 = mean3(lobe.transmission), f90 = mean3(lobe.transmission90);
  double albedo = 0;
  if (lobe.transmission_alpha2 > 0.0f && lobe.transmission_alpha2_hi > lobe.transmission_alpha2 * 1.0001f) {
    // A band: the mean of its GGX albedos over log-uniform α², as specular_flux takes a mixture's.
    const double step = series_log(double(lobe.transmission_alpha2_hi) / double(lobe.transmission_alpha2)) / 8;
    for (int j = 0; j < 8; ++j) albedo += t.ggx_albedo_at_log(series_log(lo) + (j + 0.5) * step, f0, f90) / 8;
  } else {
    albedo = t.ggx_albedo_at_log(series_log(lo), f0, f90);
  }
  return double(lobe.weight) * glm::length(glm::dvec3(lobe.normal)) * albedo;
}

double specular_flux(const Lobe& lobe) {
  const SpecAlbedoTable& t = SpecAlbedoTable::get();
  Lobe l = lobe;
  if (l.stretch > 1.0f) {
    const double f = stretch_albedo_factor(l.stretch);
    l.alpha2 = static_cast<float>(l.alpha2 * f);
    if (l.alpha2_hi > 0.0f) l.alpha2_hi = static_cast<float>(l.alpha2_hi * f);
    l.stretch = 1.0f;
  }
  double spec = 0;
  if (l.alpha2_hi > l.alpha2) {
    // A roughness mixture reflects the mean of its components' albedos: its band's over log-uniform α²
    // (midpoint rule in log α², 8 points), or its upper atom's, and its lower atom's.
    const double lo = series_log(double(l.alpha2)), f0 = mean3(l.f0), f90 = l.f90;
    if (l.skirt == 0.0f) {
      spec = t.ggx_albedo_at_log(series_log(double(l.alpha2_hi)), f0, f90);
    } else {
      const double step = series_log(double(l.alpha2_hi) / double(l.alpha2)) / 8;
      for (int k = 0; k < 8; ++k) spec += t.ggx_albedo_at_log(lo + (k + 0.5) * step, f0, f90) / 8;
    }
    spec = l.ggx * spec + (1 - l.ggx) * t.ggx_albedo_at_log(lo, f0, f90);
  } else {
    const double f0 = mean3(l.f0), f90 = l.f90;
    spec = l.skirt > 1.0f ? l.ggx * t.albedo(l.alpha2, f0, 1.0, f90) +
                                (1 - l.ggx) * t.albedo(double(l.alpha2) * l.skirt, f0, 0.0, f90)
                          : t.albedo(l.alpha2, f0, l.ggx, f90);
  }
  return double(l.weight) * glm::length(glm::dvec3(l.normal)) * spec;
}

}  // namespace svbrdf::reduction
