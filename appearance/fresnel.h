#pragma once
// Fresnel reflectance (CGPP §27.5, §26.x; Born & Wolf): Schlick's approximation, the exact
// unpolarized reflectance of a dielectric interface, and of a conductor with complex index
// η + iκ. cos_i is the cosine of the incident angle measured on the incident side (≥ 0).
#include <glm/glm.hpp>

#include "appearance/bsdf.h"

namespace svbrdf {

// Schlick 1994: F = f0 + (1 − f0)(1 − cos)^5.
inline float fresnel_schlick(float f0, float cos_i) {
  const float m = 1.0f - cos_i;
  const float m2 = m * m;
  return f0 + (1.0f - f0) * (m2 * m2 * m);
}
inline Rgb fresnel_schlick(const Rgb& f0, float cos_i) {
  const float m = 1.0f - cos_i;
  const float m2 = m * m;
  return f0 + (Rgb(1.0f) - f0) * (m2 * m2 * m);
}
// The normal-incidence reflectance of a dielectric of relative index eta: ((η−1)/(η+1))².
inline float fresnel_f0(float eta) {
  const float r = (eta - 1.0f) / (eta + 1.0f);
  return r * r;
}

// Reflectances for light polarized perpendicular (s) and parallel (p) to the plane of incidence.
struct FresnelPolarized {
  float rs = 0, rp = 0;
  float unpolarized() const { return 0.5f * (rs + rp); }
};

// Exact dielectric reflectance for relative index eta = n_transmitted / n_incident
// (eta < 1: from the denser side; past the critical angle, total internal reflection gives 1):
//   r_s = (cosi − η cost)/(cosi + η cost), r_p = (η cosi − cost)/(η cosi + cost), R = r².
FresnelPolarized fresnel_dielectric_polarized(float cos_i, float eta);
inline float fresnel_dielectric(float cos_i, float eta) { return fresnel_dielectric_polarized(cos_i, eta).unpolarized(); }

// Exact conductor reflectance for the complex relative index η + iκ (the same equations with a
// complex η and the principal square root for cos θt).
FresnelPolarized fresnel_conductor_polarized(float cos_i, float eta, float k);
inline float fresnel_conductor(float cos_i, float eta, float k) {
  return fresnel_conductor_polarized(cos_i, eta, k).unpolarized();
}
inline Rgb fresnel_conductor(float cos_i, const Rgb& eta, const Rgb& k) {
  return {fresnel_conductor(cos_i, eta.x, k.x), fresnel_conductor(cos_i, eta.y, k.y),
          fresnel_conductor(cos_i, eta.z, k.z)};
}

}  // namespace svbrdf
