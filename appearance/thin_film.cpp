#include "appearance/thin_film.h"

#include <algorithm>
#include <cmath>

#include "appearance/fresnel.h"
#include "base/math.h"

namespace svbrdf {
namespace {

// ((n_t − n_i) / (n_t + n_i))²: the normal-incidence reflectance between two dielectrics.
float ior_to_fresnel0(float transmitted_ior, float incident_ior) {
  const float r = (transmitted_ior - incident_ior) / (transmitted_ior + incident_ior);
  return r * r;
}

// The spectral sensitivity in Fourier space (Belcour & Barla 2017, §4 and their supplemental code;
// the constants as the extension's notes carry them): each of X, Y, Z is fitted by Gaussians in
// wavenumber, so its integral against cos(2π·OPD/λ) is the Gaussian's Fourier transform,
//   val·√(2π·var)·cos(pos·k)·exp(−var·k²),  k = 2π·OPD (OPD in metres),
// X with a second lobe; normalized so that OPD = 0 gives XYZ ≈ (1, 1, 1). Returned in linear
// Rec.709 (IEC 61966-2-1 matrix), with zero phase shift: a shift of 0 or π only flips the sign.
glm::vec3 sensitivity_rec709(float opd_nm) {
  const float k = 2.0f * kPi * opd_nm * 1e-9f;
  const float k2 = k * k;
  auto lobe = [&](float val, float pos, float var) {
    return val * std::sqrt(2.0f * kPi * var) * std::cos(pos * k) * std::exp(-var * k2);
  };
  const glm::vec3 xyz = glm::vec3(lobe(5.4856e-13f, 1.6810e+06f, 4.3278e+09f) + lobe(9.7470e-14f, 2.2399e+06f, 4.5282e+09f),
                                  lobe(4.4201e-13f, 1.7953e+06f, 9.3046e+09f),
                                  lobe(5.2481e-13f, 2.2084e+06f, 6.6121e+09f)) /
                        1.0685e-7f;
  return {3.2404542f * xyz.x - 1.5371385f * xyz.y - 0.4985314f * xyz.z,
          -0.9692660f * xyz.x + 1.8760108f * xyz.y + 0.0415560f * xyz.z,
          0.0556434f * xyz.x - 0.2040259f * xyz.y + 1.0572252f * xyz.z};
}

float smoothstep01(float t) {
  t = std::clamp(t, 0.0f, 1.0f);
  return t * t * (3.0f - 2.0f * t);
}

// The closed form at full film thickness, for thickness_nm > 0.
Rgb film_fresnel(float cos1, float d, float film_ior, const Rgb& base_f0, float outside_ior) {
  const float n1 = outside_ior, n2 = film_ior;
  // Snell's law into the film; no transmitted wave past the critical angle.
  const float sin2_t2 = (n1 / n2) * (n1 / n2) * (1.0f - cos1 * cos1);
  if (sin2_t2 >= 1.0f) return Rgb(1.0f);
  const float cos2 = std::sqrt(1.0f - sin2_t2);

  // First interface (outside | film): Schlick at θ1, the same reflectance both ways, T121 = 1 − R12.
  const float r12 = fresnel_schlick(ior_to_fresnel0(n2, n1), cos1);
  const float t121 = 1.0f - r12;
  // Reflection phases, 0 or π (polarization ignored): φ12 = π when the film is the rarer medium,
  // and the reflection off the outside seen from inside the film has φ21 = π − φ12.
  const float phi21 = n2 < n1 ? 0.0f : kPi;

  // First-order optical path difference of the two reflected waves, 2·n2·d·cos θ2 (Belcour & Barla
  // eq. 5: the path inside the film, so the refracted cosine).
  const float opd = 2.0f * n2 * d * cos2;
  const glm::vec3 s1 = sensitivity_rec709(opd), s2 = sensitivity_rec709(2.0f * opd);

  const Rgb n3 = iridescence_base_ior(base_f0);
  Rgb out;
  for (int c = 0; c < 3; ++c) {
    // Second interface (film | base) at θ2; φ23 = π when the base is the rarer side.
    const float r23 = fresnel_schlick(ior_to_fresnel0(n3[c], n2), cos2);
    const float phi = phi21 + (n3[c] < n2 ? kPi : 0.0f);
    // The Airy series of the two interfaces as a Fourier series in OPD (Belcour & Barla eq. 9–10):
    //   R = C0 + Σ_m 2 C_m S_m,  C0 = R12 + Rs,  Rs = T121² R23 / (1 − R12 R23),
    //   C_m = (Rs − T121) (R12 R23)^(m/2),  S_m = the sensitivity at m·OPD with phase shift m·φ.
    // φ ∈ {0, π, 2π} makes the shift the sign cos(m·φ); it is applied to this channel's own
    // spectrum, so each RGB channel is the integral of its own base's reflectance.
    const float r123 = std::min(r12 * r23, 0.9999f);
    const float sqrt_r123 = std::sqrt(r123);
    const float rs = t121 * t121 * r23 / (1.0f - r123);
    float value = r12 + rs;
    float cm = rs - t121;
    cm *= sqrt_r123;
    value += 2.0f * cm * std::cos(phi) * s1[c];
    cm *= sqrt_r123;
    value += 2.0f * cm * std::cos(2.0f * phi) * s2[c];
    // XYZ → Rec.709 leaves the gamut for saturated fringes; a reflectance stays in [0, 1].
    out[c] = std::clamp(value, 0.0f, 1.0f);
  }
  return out;
}

}  // namespace

Rgb iridescence_base_ior(const Rgb& base_f0) {
  const Rgb s = glm::sqrt(glm::clamp(base_f0, Rgb(0.0f), Rgb(0.9999f)));
  return (Rgb(1.0f) + s) / (Rgb(1.0f) - s);
}

Rgb iridescence_fresnel(float cos_theta1, float thickness_nm, float film_ior, const Rgb& base_f0, float outside_ior) {
  const float cos1 = std::clamp(cos_theta1, 0.0f, 1.0f);
  const float d = std::max(thickness_nm, 0.0f);
  const float film_weight = smoothstep01(d / kIridescenceFadeThickness);
  const Rgb no_film = fresnel_schlick(base_f0, cos1);
  if (film_weight == 0.0f) return no_film;
  return glm::mix(no_film, film_fresnel(cos1, d, film_ior, base_f0, outside_ior), film_weight);
}

}  // namespace svbrdf
