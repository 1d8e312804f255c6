#pragma once
// One lobe of a BRDF-averaged MIP texel, and the effective BRDF f_eff of ../shared/spec/brdf-mip.md
// evaluated for it.
//
// The glTF model of brdf-models.md splits into a part that is linear in the texel's colors and a
// part that is not. With F0 = mix(0.04, c, m) and ρ = (1 − m)·c,
//   f = 0.96·(1 − w)·ρ/π + D·V·(F0 + (1 − F0)·w),       w = (1 − |wo·h|)^5,
// (dielectric = mix(c/π, s, 0.04 + 0.96·w) and metal = s·(c + (1 − c)·w) give exactly this). w and
// h depend on the direction pair only, never on the normal, so ρ and F0 average linearly; only the
// normal and the roughness α enter nonlinearly. A lobe therefore carries
//   weight  — the fraction of the texel's area it stands for, times the factor by which a merge
//             rescaled its specular part to keep the flux of the lobes it replaced (lobe_reduction.h;
//             ρ is divided by the same factor, so weight·ρ stays the exact diffuse amplitude),
//   diffuse — the mean ρ, f0 — the mean F0 (linear, exact under averaging),
//   diffuse90, f90 — the diffuse and specular factors at grazing incidence (w = 1), linear too; 0 and 1
//             for the plain glTF BRDF, other values under KHR_materials_specular and _ior (below),
//   normal  — the mean of the unit shading normals, unnormalized: its length says how much they spread,
//   alpha2, alpha2_hi, ggx, skirt — the specular shape about n̂ = normalize(normal) (below),
// and its microfacet distribution D is one of two shapes, both normalized, both exactly GGX(α²) for a
// level-0 texel (alpha2_hi = 0, ggx = 1):
//   - a roughness mixture (alpha2_hi > alpha2): a GGX atom at l = alpha2 of share 1 − β and an upper
//     part of share β = ggx, which is (skirt = 1) GGX averaged over α² log-uniform in [l, h] =
//     [alpha2, alpha2_hi], in closed form
//       D_band = L(l, h) / (π·(|n×h|² + (n·h)²·l)·(|n×h|² + (n·h)²·h)),  L(l, h) = (h − l)/ln(h/l),
//     or (skirt = 0) a second GGX atom at h (a two-point mixture). β = 1 with the band is the plain
//     log-uniform mixture; the atom keeps a sharp peak that a band alone cannot (lobe_fit.cpp);
//   - a spread core (alpha2_hi = 0, ggx = μ ≤ 1): D = μ·D_GGX(α²) + (1 − μ)·D_Beckmann(c·α²), c = skirt ≥ 1
//     (a skirt wider than the core: lobe_fit.cpp, set_shape).
// Why two: far from its peak a GGX lobe falls as α²/(π·tan⁴θ·cos⁴θ), so a mixture's tail is set by
// the mean α² (A) and its peak by the mean 1/α² (P). Lobes of different roughness have A·P > 1 —
// heavier tails than any one GGX; the log-uniform mixture matches both moments (A = L(l, h),
// P = L/(l·h)). Narrow lobes tilted by different small angles widen their union's core (LEAN adds the
// normals' spread to α²) but add nothing to its tail: A·P < 1, lighter tails than GGX; the Beckmann
// share (Gaussian slopes, LEAN's own model of the spread) carries those, μ = A·P. One GGX of the widened
// α² would raise every off-specular value by the ratio of widened to base α² (×4 for α = 0.01 lobes
// tilted ±1°).
// and reflects, in the geometric tangent frame,
//   weight · [(0.96·(1 − w)·ρ + w·ρ90)/π + D·V·(F0 + (F90 − F0)·w)] · (normal·wi) / wi.z,
// (ρ90 = diffuse90, F90 = f90: the plain glTF BRDF has ρ90 = 0 and F90 = 1, the form above),
// with D as above and V the glTF (GGX, height-correlated Smith) visibility about n̂ — for a roughness
// mixture the mean of its components' V (atoms and band) weighted by their D at the half vector, for a spread core's
// Beckmann share and its skirt at the GGX share's α² (the masking functions differ by a few percent at
// grazing angles only; weighting V by the shares' D moved polished granite's highlight by < 0.01 %) — and 0
// when n̂·wi ≤ 0, n̂·wo ≤ 0, wi.z ≤ 0 or wo.z ≤ 0. A level-0 texel is one lobe of weight 1 with a unit normal and
// this is then exactly f_eff,x = f_x · max(0, n_x·wi)/wi.z. For a merged lobe, (normal·wi) =
// E[n_x]·wi is the exact mean of the texels' cosine factors while no normal is below the light's
// horizon (the diffuse term is then exact, the design notes' E[ρ·n]); the specular part keeps the
// same factor so the lobe reflects the same flux as its texels.
//
// Stretched shapes. Every shape above is a density of the microfacets' slopes m = −(h_t, h_b)/(n·h)
// that depends on |m|² = tan²θ only, divided by cos⁴θ. A lobe with a stretch (direction t in n̂'s
// tangent plane, b = n̂ × t, ratio r ≥ 1) takes the same density of the stretched slopes
// S^(−1/2)·m, S = diag(r, 1/r) in (t, b): |m|² becomes (h_t²/r + h_b²·r)/(n·h)², and det S = 1
// keeps every shape normalized. This is the anisotropic GGX of Heitz 2014 ("Understanding the
// Masking-Shadowing Function in Microfacet-Based BRDFs", §5.3, eq. 85 and 86: the slope stretch) with
// α_t = α·√r and α_b = α/√r, so α² stays the geometric mean α_t·α_b and the slopes' second moments
// are α²·S (the isotropic lobe's α²·I stretched). Its Smith Λ stretches the same way: for a direction
// w at cos θ = c to n̂, α²·(1 − c²) = α²·(w_t² + w_b²) under V's roots becomes α²·(r·w_t² + w_b²/r).
// KHR_materials_anisotropy's lobe (α along its direction mix(α, 1, strength²), α across it, the
// renderer's appearance/gltf_surface_bsdf.h) is the GGX atom with r = α_t/α_b and α² = α_t·α_b
// (lobe_from_texel), exactly. The direction t is the lobe's stretch_dir (a direction of the geometric
// tangent frame's x–y plane, as the glTF tangent and bitangent span it) projected orthogonally onto
// n̂'s tangent plane, as the renderer expresses the anisotropy direction in a normal-mapped shading
// frame (render/surface.cpp); the normals' spread (the horizons below) stays isotropic. A lobe with
// r = 1 takes none of this: its arithmetic is that of the isotropic shapes, bit for bit.
//
// Transmission. A thin-walled KHR_materials_transmission turns the base's reflection lobe over: its
// BTDF is the specular V·D at wi mirrored through the surface plane (appearance/gltf_surface_bsdf.h),
// in the frame of the texel's normal n_x. So a lobe transmits, for wi below the geometric surface, as
// it reflects the pair (wi', wo) with wi' the mirror of wi through n̂'s plane — exactly for one texel
// (n̂ = n_x), its clipped cosine E[max(0, n·wi')] = E[max(0, −n·wi)] for spread normals — with the
// factors τ + (τ90 − τ)·w in place of the Fresnel term and no diffuse part, w the Schlick weight at
// |wo·h'|, f_eff's denominator |wi.z|. τ and τ90 are linear in the texels' parameters as ρ is, so a
// merge averages them as it averages ρ. The shape is another matter: a thin wall passes light straight
// through whatever its normal's tilt (at wi = −wo the mirrored half vector is the texel's normal), so
// the texels' normals, which spread the union's reflection, do not spread its transmission. A lobe
// transmits through a shape of its own, about its normal, with its spread's horizons and a stretch of
// its own (transmission_stretch, its texels' anisotropy: at level 0 the reflection's; a merge's the
// det-1 scaling of its members' amplitude-weighted α_T²·S_T, where the reflection's stretch adds the
// normals' offsets 2·ττᵀ, slope_stretch.h, which a thin wall's transmission does not see):
// GGX of transmission_alpha2 (its α² at level 0), or the reflection's log-uniform band over
// [transmission_alpha2, transmission_alpha2_hi]. A merge gives it the union's tail and peak moments,
// A = E[α²] and P = E[1/α²] over the members' amplitudes (a band's are L(l, h) and L/(l·h)): GGX of
// α² = 1/P where A·P = 1 (one roughness), else the band with l·h = A/P and sinh(s)/s = √(A·P), s =
// ln(h/l)/2 — the two moments that set a union's peak and its tails (the reflection's "Why two" above;
// one GGX of the union's peak left lobes of roughnesses 100× apart 10 % dark 35° off the straight-
// through direction). Its τ is scaled by the merge to keep the union's transmitted flux (albedo_table.h
// transmission_flux).
#include <algorithm>
#include <cmath>
#include <type_traits>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include <glm/glm.hpp>

#include "appearance/gltf.h"
#include "appearance/microfacet_core.h"
#include "base/math.h"
#include "base/series_log.h"
#include "textures/material_texels.h"

namespace svbrdf {

struct Lobe {
  float weight = 0.0f;
  glm::vec3 diffuse{0.0f};
  glm::vec3 f0{0.0f};
  glm::vec3 diffuse90{0.0f};  // ρ90: the diffuse factor at w = 1 (specular_layer below)
  float f90 = 1.0f;           // F90: the specular Fresnel at w = 1
  glm::vec3 f0_tint{0.0f};    // the part of F0 a tint of the base color scales (tinted below)
  float coat = 0.0f;          // the mean clear coat weight over its texels, which the coat's Fresnel
                              // takes from the lobe (coat_layer.h; 0 without a coat)
  float sheen = 0.0f;         // the mean max(sheen colour) over its texels, which scales the lobe by the
                              // sheen's albedo and weights the sheen about its normal (sheen_layer.h)
  glm::vec3 normal{0.0f, 0.0f, 1.0f};
  float alpha2 = 1e-6f;     // GGX α² (a roughness mixture's lower end)
  float ggx = 1.0f;         // μ, the GGX share of a spread core; β, the upper part's share of a roughness mixture
  float alpha2_hi = 0.0f;   // > alpha2: a roughness mixture's upper end
  float skirt = 1.0f;       // c ≥ 1: a spread core's Beckmann share is at c·alpha2 (its skirt); a roughness
                            // mixture's upper part: 1 the band [alpha2, alpha2_hi], 0 an atom at alpha2_hi
  // A slope stretch (the shapes' anisotropy, "Stretched shapes" below): the direction of the wider
  // slopes, a unit vector in the geometric tangent frame's x–y plane, projected onto n̂'s tangent plane,
  // and the ratio r ≥ 1 of the slopes' widths along it and across it; r = 1 is isotropic.
  glm::vec2 stretch_dir{1.0f, 0.0f};
  float stretch = 1.0f;
  // A thin-walled transmission (KHR_materials_transmission without a volume, "Transmission" below):
  // the factors of the lobe's BTDF at w = 0 and w = 1, 0 without one.
  glm::vec3 transmission{0.0f};
  glm::vec3 transmission90{0.0f};
  float transmission_alpha2 = 0.0f;     // the transmission's GGX α² ("Transmission" above); 0 without one
  float transmission_alpha2_hi = 0.0f;  // > transmission_alpha2: its shape is the log-uniform band
                                        // [transmission_alpha2, transmission_alpha2_hi]
  // The transmission's own slope stretch (as stretch_dir and stretch above): its texels' anisotropy
  // without the spread of their normals, which the reflection's stretch holds ("Transmission" above).
  glm::vec2 transmission_stretch_dir{1.0f, 0.0f};
  float transmission_stretch = 1.0f;
  // A diffuse transmission (KHR_materials_diffuse_transmission): the factors of the lobe's Lambertian
  // BTDF at w = 0 and w = 1, 0 without one (mip/diffuse_transmission.h).
  glm::vec3 diffuse_transmission{0.0f};
  glm::vec3 diffuse_transmission90{0.0f};
};

// The glTF layering of KHR_materials_specular (its "fresnel_mix", appearance/gltf.h gltf_layers):
// with the dielectric's f0 = min(((ior − 1)/(ior + 1))²·colour, 1) and fr = f0 + (1 − f0)·w,
//   dielectric = (1 − s·max(fr))·ρ/π + s·fr·D·V,   metal = (c + (1 − c)·w)·D·V,   f = mix(dielectric, metal, m).
// max over channels of f0 + (1 − f0)·w is max(f0) + (1 − max(f0))·w (each channel rises with f0 for
// w ≤ 1), so every factor is linear in w, and the lobe's four factors are
//   0.96·ρ = (1 − m)·c·(1 − s·max(f0)),  ρ90 = (1 − m)·c·(1 − s),
//   F0 = (1 − m)·s·f0 + m·c,            F90 = (1 − m)·s + m.
// For the plain layer (f0 = 0.04, s = 1) these are ρ = (1 − m)·c, ρ90 = 0, F0 = mix(0.04, c, m), F90 = 1.
inline float dielectric_f0(float ior) {
  const float r = (ior - 1.0f) / (ior + 1.0f);
  return r * r;
}

// The level-0 lobe of a texel with glTF parameters (linear base color, metallic, perceptual
// roughness), a unit shading normal and its specular layer: α = max(roughness², 1e-3) as brdf-models.md
// defines.
// With an anisotropy (KHR_materials_anisotropy) the GGX atom is stretched: α_t = mix(α, 1, strength²)
// along its direction and α across it, as the renderer computes them, make α² = α_t·α and r = α_t/α
// ("Stretched shapes" above).
//
// With a transmission T (KHR_materials_transmission, thin-walled) the dielectric's base is
// mix(diffuse, specular_btdf·c, T): ρ and ρ90 take 1 − T, and the BTDF's factors are
//   τ = (1 − m)·c·T·(1 − s·max(f0)),   τ90 = (1 − m)·c·T·(1 − s)
// (the base's 1 − s·max(fr) linear in w as for ρ; the plain layer's τ = 0.96·(1 − m)·c·T, τ90 = 0).
inline Lobe lobe_from_texel(const glm::vec3& base_color, float metallic, float roughness, const glm::vec3& normal,
                            float weight = 1.0f, const SpecularLayer& layer = {}, const AnisotropyLayer& aniso = {},
                            float transmission = 0.0f) {
  const float alpha = gltf_alpha(roughness);
  Lobe l;
  l.weight = weight;
  l.normal = normal;
  l.alpha2 = alpha * alpha;
  const float strength = std::clamp(aniso.strength, 0.0f, 1.0f);
  if (strength > 0.0f) {
    const float alpha_t = alpha + (1.0f - alpha) * (strength * strength);
    l.alpha2 = alpha_t * alpha;
    l.stretch = alpha_t / alpha;
    l.stretch_dir = aniso.direction;
  }
  const float t = std::clamp(transmission, 0.0f, 1.0f);
  if (layer.plain()) {
    // The plain layer in its own arithmetic, so that its lobes stay bit for bit what they always were.
    l.diffuse = (1.0f - metallic) * base_color;
    l.f0 = glm::mix(glm::vec3(0.04f), base_color, metallic);
    l.f0_tint = metallic * base_color;
    if (t > 0.0f) {
      l.transmission = (0.96f * t) * l.diffuse;
      l.diffuse *= 1.0f - t;
      l.transmission_alpha2 = l.alpha2;
      l.transmission_stretch = l.stretch, l.transmission_stretch_dir = l.stretch_dir;
    }
    return l;
  }
  const glm::vec3 f0 = glm::min(dielectric_f0(layer.ior) * layer.color, glm::vec3(1.0f));
  const float f0_max = std::max(f0.r, std::max(f0.g, f0.b));
  const glm::vec3 rho = (1.0f - metallic) * base_color;
  l.diffuse = rho * ((1.0f - layer.specular * f0_max) / 0.96f);
  l.diffuse90 = rho * (1.0f - layer.specular);
  l.f0 = (1.0f - metallic) * layer.specular * f0 + metallic * base_color;
  l.f90 = (1.0f - metallic) * layer.specular + metallic;
  l.f0_tint = metallic * base_color;
  if (t > 0.0f) {
    l.transmission = rho * (t * (1.0f - layer.specular * f0_max));
    l.transmission90 = t * l.diffuse90;
    l.diffuse *= 1.0f - t;
    l.diffuse90 *= 1.0f - t;
    l.transmission_alpha2 = l.alpha2;
    l.transmission_stretch = l.stretch, l.transmission_stretch_dir = l.stretch_dir;
  }
  return l;
}

// A tint v of the base color (glTF's COLOR_0: c → c·v, glTF 2.0 §3.9.2) in a lobe's factors. Of the
// four (specular_layer above) ρ and ρ90 are (1 − m)·c times factors free of c, and F0 is the sum of
// the untinted (1 − m)·s·f0 and the tintable m·c; F90 holds no c. Each is linear in the texels' colors
// and a merged lobe averages each linearly (lobe_reduction.h; a merge's flux rescaling scales weight
// and ρ, never F0), so with f0_tint the mean of m·c a lobe tinted by
//   ρ·v, ρ90·v, F0 + f0_tint·(v − 1), F90
// is exactly what the same merges of the tinted texels make, at any level, for a tint that is one
// value over the texel's footprint (COLOR_0 is interpolated from the vertices, smooth on a texel's
// scale). What the tint does not move is the lobes' shapes, fitted with the untinted colours' weights,
// nor the texel's radial correction (weighted by untinted F0, radial_correction.h): where a tint moves
// metal and dielectric texels of one lobe apart, those weights are off to second order (tint_test.cpp
// measures it against the exact reference of the tinted texels).
inline Lobe tinted(Lobe l, const glm::vec3& v) {
  l.diffuse *= v;
  l.diffuse90 *= v;
  l.transmission *= v;  // (1 − m)·c times factors free of c, as ρ
  l.transmission90 *= v;
  l.f0 += l.f0_tint * (v - 1.0f);
  l.f0_tint *= v;
  return l;
}

// What a direction pair contributes independently of any lobe: h and the Schlick weight w.
template <class T>
struct PairTerms {
  glm::vec<3, T> wi{0, 0, 1}, wo{0, 0, 1}, h{0, 0, 1};
  T fresnel_w = 0;     // (1 − |wo·h|)^5
  T inv_wi_z = 0;      // 1/wi.z, the f_eff factor's denominator, once for all the lobes
  bool valid = false;  // both above the geometric horizon
};

template <class T>
PairTerms<T> pair_terms(const glm::vec<3, T>& wi, const glm::vec<3, T>& wo) {
  PairTerms<T> p;
  p.wi = wi;
  p.wo = wo;
  if (!(wi.z > 0) || !(wo.z > 0)) return p;
  p.h = glm::normalize(wi + wo);
  p.fresnel_w = schlick_weight(std::abs(glm::dot(wo, p.h)));
  p.inv_wi_z = T(1) / wi.z;
  p.valid = true;
  return p;
}

// The horizons of a lobe whose texels' normals spread about n̂. A texel contributes only while its
// own normal faces both directions, and its cosine factor is max(0, n_x·wi). With the normals' slopes
// modelled as an isotropic Gaussian of per-axis variance σ² about n̂, n_x·w is about normal with
// mean n̂·w and standard deviation s = σ·sin θ (θ the angle of w to n̂), so
//   E[max(0, n_x·wi)] = len·(μ·Φ(μ/s) + s·φ(μ/s)) with μ = n̂·wi   (the mean of a clipped normal),
//   P(n_x·wo > 0)     = Φ(μ/s)                       with μ = n̂·wo,
// which replace the hard cut-offs of one texel. σ² comes from the mean normal's length as in
// Toksvig 2005: σ² = (1 − len)/len. For len = 1 (one texel, or texels sharing their normal) they are
// exactly max(0, n·wi) and [n·wo > 0].
template <class T>
struct LobeShape {
  glm::vec<3, T> n{0, 0, 1};  // n̂
  T len = 1;                  // |mean normal|
  T sigma = 0;                // spread of the normals' slopes (0: a hard horizon)
  T alpha2 = 1;
  T ggx = 1;  // μ, the GGX share of D
  T skirt = 1;  // c: the Beckmann share's α² is c·alpha2
  T alpha2_hi = 0;             // a roughness mixture's upper end (0: not a mixture)
  T lmean = 0;                 // its band's logarithmic mean L(l, h) (0: no band)
  T node_a2[3] = {0, 0, 0};    // the band's 3-point Gauss–Legendre nodes in ln α², for V (lobe_brdf)
  bool two_point = false;      // a roughness mixture whose upper part is an atom at alpha2_hi
  // The stretch ("Stretched shapes" at the top): its frame in n̂'s tangent plane and r, 1/r.
  bool stretched = false;
  glm::vec<3, T> st{1, 0, 0}, sb{0, 1, 0};
  T r = 1, inv_r = 1;
  bool valid = false;
};

// A shape's band over [lo, hi] (alpha2 = lo, alpha2_hi = hi set): its logarithmic mean and, with_nodes,
// the quadrature nodes lobe_brdf's V needs (not lobe_d).
template <class T>
void set_band(LobeShape<T>& s, float lo, float hi, bool with_nodes) {
  T x, span;  // h/l − 1 and ln(h/l)
  if constexpr (std::is_same_v<T, float>) {
    // Both from the one float ratio, so that x/span (smooth in the ratio) keeps its precision.
    const float ratio = hi / lo;
    x = ratio - 1.0f;
    span = series_logf(ratio);
  } else {
    const double ratio = double(hi) / double(lo);
    x = T(ratio - 1.0);
    span = T(series_log(ratio));  // within 1e-9
  }
  s.lmean = s.alpha2 * x / span;
  if (with_nodes) {
    // l·(h/l)^t at t = ½ ∓ √(3/20) and ½: the outer two are l·e and h/e with e = (h/l)^0.1127.
    const T x01 = T(0.11270166537925831) * span;
    T e;
    if constexpr (std::is_same_v<T, float>) e = series_exp(x01);  // every hit's lobes: no libm call
    else e = std::exp(x01);
    s.node_a2[0] = s.alpha2 * e;
    s.node_a2[1] = std::sqrt(s.alpha2 * s.alpha2_hi);
    s.node_a2[2] = s.alpha2_hi / e;
  }
}

// A shape's stretch of ratio r along dir (s.n set): dir projected onto n̂'s tangent plane; a direction
// along n̂ itself (n̂ in the x–y plane, no lobe a texel makes) takes the plane's direction across z.
// r ≤ 1 is none.
template <class T>
void set_shape_stretch(LobeShape<T>& s, float r, const glm::vec2& dir) {
  s.stretched = false;
  if (!(r > 1.0f)) return;
  const glm::vec<3, T> d(T(dir.x), T(dir.y), T(0));
  glm::vec<3, T> t = d - s.n * glm::dot(s.n, d);
  if (!(glm::dot(t, t) > T(1e-12))) t = glm::cross(s.n, glm::vec<3, T>(0, 0, 1));
  s.st = glm::normalize(t);
  s.sb = glm::cross(s.n, s.st);
  s.r = T(r);
  s.inv_r = T(1) / s.r;
  s.stretched = true;
}

// with_nodes: also the quadrature nodes lobe_brdf's V needs (not lobe_d).
template <class T>
LobeShape<T> lobe_shape(const Lobe& lobe, bool with_nodes = true) {
  LobeShape<T> s;
  const glm::vec<3, T> nbar(lobe.normal);
  const T len2 = glm::dot(nbar, nbar);
  if (!(lobe.weight > 0) || !(len2 > 0)) return s;
  s.len = std::sqrt(len2);
  const T inv_len = T(1) / s.len;  // one division for the four below (this runs for every lobe of every hit)
  s.n = nbar * inv_len;
  const T var = s.len < T(1) ? (T(1) - s.len) * inv_len : T(0);
  s.sigma = var > T(1e-7) ? std::sqrt(var) : T(0);
  s.alpha2 = T(lobe.alpha2);
  set_shape_stretch(s, lobe.stretch, lobe.stretch_dir);
  s.ggx = std::clamp(T(lobe.ggx), T(0), T(1));
  s.skirt = std::max(T(1), T(lobe.skirt));
  if (lobe.alpha2_hi > lobe.alpha2 * 1.0001f) {
    s.alpha2_hi = T(lobe.alpha2_hi);
    s.two_point = lobe.skirt == 0.0f;  // (s.skirt is 1 for either kind: a mixture has no skirt)
  }
  if (s.alpha2_hi > 0 && !s.two_point) set_band(s, lobe.alpha2, lobe.alpha2_hi, with_nodes);
  s.valid = true;
  return s;
}

// One side of a lobe for a direction with cos θ = c to n̂: the factor it contributes (the expected
// clipped cosine for wi, the facing probability for wo) and the cosine the GGX terms use (clamped
// away from 0 where a spread lobe still reflects past its mean horizon). factor = 0: no contribution.
template <class T>
struct LobeSide {
  T factor = 0;
  T c = 0;
};

template <class T>
inline T standard_normal_cdf(T x) {
  return T(0.5) * std::erfc(-x * T(0.70710678118654752440));
}

// Whether c lies more than eight deviations s = σ·sin θ above the horizon, where the clipping is nil
// (Φ = 1 − 6e-16, φ = 5e-15): the common case, decided on squares (no root, no division).
template <class T>
bool far_above_horizon(const LobeShape<T>& s, T c) {
  const T c2 = c * c;
  return c > 0 && c2 > T(64) * (s.sigma * s.sigma) * (T(1) - c2);
}

template <class T>
LobeSide<T> lobe_wi_side(const LobeShape<T>& s, T c) {
  if (s.sigma == 0) return c > 0 ? LobeSide<T>{c * s.len, c} : LobeSide<T>{};
  if (far_above_horizon(s, c)) return {c * s.len, std::max(c, T(1e-4))};
  const T sd = s.sigma * std::sqrt(std::max(T(0), T(1) - c * c)) + T(1e-12);
  const T x = c / sd;
  const T factor = s.len * (c * standard_normal_cdf(x) + sd * T(0.39894228040143267794) * std::exp(T(-0.5) * x * x));
  return {factor, std::max(c, T(1e-4))};
}

template <class T>
LobeSide<T> lobe_wo_side(const LobeShape<T>& s, T c) {
  if (s.sigma == 0) return c > 0 ? LobeSide<T>{T(1), c} : LobeSide<T>{};
  if (far_above_horizon(s, c)) return {T(1), std::max(c, T(1e-4))};
  const T sd = s.sigma * std::sqrt(std::max(T(0), T(1) - c * c)) + T(1e-12);
  return {standard_normal_cdf(c / sd), std::max(c, T(1e-4))};
}

// D of a lobe at a half vector with n̂·h = ch and n̂×h = nxh (the shapes at the top of this file), with
// 1 − (n·h)² written as |n×h|², which keeps its precision at the peak of sharp lobes.
//   D_GGX = α² / (π·(|n×h|² + (n·h)²·α²)²)                    (ggx_d_terms, microfacet_core.h)
//   its log-uniform mixture: ∫ α²/(α² + t)² dα²/α² over [l, h] / ln(h/l) = (1/(l + t) − 1/(h + t))/ln(h/l)
//   with t = tan²θ, which is L(l, h)/((l + t)(h + t)) (÷ π·cos⁴θ)
//   D_Beckmann = exp(−tan²θ/α²) / (π·α²·cos⁴θ), tan²θ = |n×h|²/(n·h)²   (Walter et al. 2007, eq. 25)
// The |n×h|² the shapes take: (h·t)²/r + (h·b)²·r for a stretched lobe, with h·t = (n×h)·b and
// h·b = −(n×h)·t (n̂ unit), which keep their precision at the peak as |n×h|² does.
template <class T>
T shape_sin2(const LobeShape<T>& s, const glm::vec<3, T>& nxh) {
  if (!s.stretched) return glm::dot(nxh, nxh);
  const T ht = glm::dot(nxh, s.sb), hb = glm::dot(nxh, s.st);
  return ht * ht * s.inv_r + hb * hb * s.r;
}

// α²·(1 − c²) under the roots of V for a direction w: α²·(r·(w·t)² + (w·b)²/r) stretched.
template <class T>
T stretched_tangent2(const LobeShape<T>& s, const glm::vec<3, T>& w) {
  const T wt = glm::dot(w, s.st), wb = glm::dot(w, s.sb);
  return wt * wt * s.r + wb * wb * s.inv_r;
}

// lobe_d below with |n×h|² given as shape_sin2 makes it.
template <class T>
T lobe_d_sin2(const LobeShape<T>& s, T ch, T sin2) {
  if (!(ch > 0)) return T(0);
  const T a2 = s.alpha2;
  const T denom = sin2 + ch * ch * a2;
  if (s.alpha2_hi > 0) {
    // A roughness mixture: its atom at l, and its band or its atom at h.
    const T denom_hi = sin2 + ch * ch * s.alpha2_hi;
    const T upper = s.two_point ? s.alpha2_hi / (denom_hi * denom_hi) : s.lmean / (denom * denom_hi);
    T d = s.ggx * upper;
    if (s.ggx != T(1)) d += (T(1) - s.ggx) * a2 / (denom * denom);
    return d * kInvPiOf<T>;
  }
  T d = s.ggx * ggx_d_terms(a2, sin2, ch * ch);
  if (s.ggx != T(1)) {
    // Past tan²θ/α² = 60 the Beckmann share is below e⁻⁶⁰ of its peak: skipped, which also keeps
    // 0·∞ out at grazing half vectors.
    const T b2 = a2 * s.skirt;
    const T c2 = ch * ch, x = sin2 / (c2 * b2);
    if (x < T(60)) {
      T ex;
      if constexpr (std::is_same_v<T, float>) ex = series_exp(-x);
      else ex = std::exp(-x);
      d += (T(1) - s.ggx) * ex * kInvPiOf<T> / (b2 * c2 * c2);
    }
  }
  return d;
}

template <class T>
T lobe_d(const LobeShape<T>& s, T ch, const glm::vec<3, T>& nxh) {
  return lobe_d_sin2(s, ch, shape_sin2(s, nxh));
}

// The specular V·D of a lobe for one pair, given the cosines of its two sides (LobeSide::c).
template <class T>
T lobe_vd(const LobeShape<T>& s, const PairTerms<T>& p, T ci, T co) {
  const T ch = glm::dot(s.n, p.h);
  const T sin2 = shape_sin2(s, glm::cross(s.n, p.h));
  const T d = lobe_d_sin2(s, ch, sin2);
  // Height-correlated Smith visibility of glTF (brdf-models.md, `gltf`) at α² = a2; stretched, each
  // root's α²·(1 − c²) is α²·q (stretched_tangent2).
  T qi = 0, qo = 0;
  if (s.stretched) qi = stretched_tangent2(s, p.wi), qo = stretched_tangent2(s, p.wo);
  const auto visibility = [&](T a2) {
    if (!s.stretched) return smith_ggx_visibility(a2, ci, co);
    return T(0.5) / (co * std::sqrt(ci * ci + a2 * qi) + ci * std::sqrt(co * co + a2 * qo));
  };
  T vis = 0;  // (every branch below sets it; clang cannot follow `lanes`)
  if (s.two_point && ch > 0) {
    // A two-point mixture: each atom's V weighted by its share of D at this half vector.
    const T t = sin2 / (ch * ch), al = s.alpha2, ah = s.alpha2_hi;
    const T dl = (T(1) - s.ggx) * al / ((al + t) * (al + t)), dh = s.ggx * ah / ((ah + t) * (ah + t));
    vis = (dl * visibility(al) + dh * visibility(ah)) / (dl + dh);
  } else if (s.lmean > 0 && ch > 0) {
    // A roughness mixture: V of each component weighted by its share of D at this half vector,
    // ∫ D_a·V_a da/a / ∫ D_a da/a over log-uniform a = α², by 3-point Gauss–Legendre in ln a, and
    // the atom at l with its share 1 − β.
    const T t = sin2 / (ch * ch);
    constexpr T kW[3] = {T(5) / T(18), T(8) / T(18), T(5) / T(18)};
    bool lanes = false;  // whether the four lanes below took it (isotropic lobes, in float)
#if defined(__SSE2__)
    if constexpr (std::is_same_v<T, float>) {
      if (!s.stretched) {
      lanes = true;
      // The three nodes side by side (the renderer's eval: 2 square roots and 2 divisions of four
      // lanes instead of 6 and 6); the fourth lane is the atom at l (weight 0 without one). It is
      // smith_ggx_visibility (microfacet_core.h) over four lanes, each weighted by its share of D.
      const T atom = (T(1) - s.ggx) / s.ggx;  // relative to the band's weights (β > 0: lobe_fit.cpp)
      const __m128 a = _mm_setr_ps(s.node_a2[0], s.node_a2[1], s.node_a2[2], s.alpha2);
      const __m128 wk = _mm_setr_ps(kW[0], kW[1], kW[2], atom);
      const __m128 one = _mm_set1_ps(1.0f), r = _mm_div_ps(one, _mm_add_ps(a, _mm_set1_ps(t)));
      const __m128 dk = _mm_mul_ps(_mm_mul_ps(wk, a), _mm_mul_ps(r, r));
      const __m128 om = _mm_sub_ps(one, a);
      const __m128 sum = _mm_add_ps(
          _mm_mul_ps(_mm_set1_ps(co), _mm_sqrt_ps(_mm_add_ps(a, _mm_mul_ps(om, _mm_set1_ps(ci * ci))))),
          _mm_mul_ps(_mm_set1_ps(ci), _mm_sqrt_ps(_mm_add_ps(a, _mm_mul_ps(om, _mm_set1_ps(co * co))))));
      const __m128 num = _mm_div_ps(_mm_mul_ps(_mm_set1_ps(0.5f), dk), sum);
      alignas(16) float n4[4], d4[4];
      _mm_store_ps(n4, num);
      _mm_store_ps(d4, dk);
      vis = (n4[0] + n4[1] + n4[2] + n4[3]) / (d4[0] + d4[1] + d4[2] + d4[3]);
      }
    }
#endif
    if (!lanes) {
      T num = 0, den = 0;
      for (int k = 0; k < 3; ++k) {
        const T a = s.node_a2[k], dk = s.ggx * kW[k] * a / ((a + t) * (a + t));
        num += dk * visibility(a);
        den += dk;
      }
      if (s.ggx != T(1)) {
        const T a = s.alpha2, dk = (T(1) - s.ggx) * a / ((a + t) * (a + t));
        num += dk * visibility(a);
        den += dk;
      }
      vis = num / den;
    }
  } else {
    vis = visibility(s.alpha2);
  }
  return vis * d;
}

// The glTF terms of a lobe for one pair, given its two sides: (0.96·(1 − w)·ρ + w·ρ90)/π + D·V·(F0 + (F90 − F0)·w).
// spec_scale multiplies the specular term (a coarse texel's radial correction, radial_correction.h).
template <class T>
glm::vec<3, T> lobe_brdf(const Lobe& lobe, const LobeShape<T>& s, const PairTerms<T>& p, T ci, T co, T spec_scale = T(1)) {
  using V3 = glm::vec<3, T>;
  const T vd = lobe_vd(s, p, ci, co);
  const T w = p.fresnel_w;
  const V3 f0(lobe.f0), rho(lobe.diffuse), rho90(lobe.diffuse90);
  return (T(0.96) * (T(1) - w) * kInvPiOf<T>) * rho + (w * kInvPiOf<T>) * rho90 +
         (vd * spec_scale) * (f0 + (V3(T(lobe.f90)) - f0) * w);
}

// weight · f_eff of one lobe for one pair (see the top of this file), in precision T. `sides`, when
// given, receives the product of its two sides' factors (0 where the lobe contributes nothing): what a
// coated texel's cosine factor sums (coat_layer.h CoatCosine), so that it costs no second evaluation.
template <class T>
glm::vec<3, T> lobe_eval(const Lobe& lobe, const LobeShape<T>& s, const PairTerms<T>& p, T spec_scale = T(1),
                         T* sides = nullptr) {
  using V3 = glm::vec<3, T>;
  if (sides) *sides = 0;
  if (!p.valid || !s.valid) return V3(0);
  const LobeSide<T> i = lobe_wi_side(s, glm::dot(s.n, p.wi));
  if (!(i.factor > 0)) return V3(0);
  const LobeSide<T> o = lobe_wo_side(s, glm::dot(s.n, p.wo));
  if (!(o.factor > 0)) return V3(0);
  if (sides) *sides = i.factor * o.factor;
  return (T(lobe.weight) * i.factor * o.factor * p.inv_wi_z) * lobe_brdf(lobe, s, p, i.c, o.c, spec_scale);
}

template <class T>
glm::vec<3, T> lobe_eval(const Lobe& lobe, const PairTerms<T>& p) {
  return lobe_eval(lobe, lobe_shape<T>(lobe), p);
}

// Whether a lobe transmits ("Transmission" at the top).
inline bool transmits(const Lobe& l) {
  return l.transmission.r > 0.0f || l.transmission.g > 0.0f || l.transmission.b > 0.0f || l.transmission90.r > 0.0f ||
         l.transmission90.g > 0.0f || l.transmission90.b > 0.0f;
}

// The shape a lobe transmits through ("Transmission" at the top): GGX of its transmission_alpha2 (its own
// α² where it has none) or its band, about the lobe's normal, with the lobe's spread and the
// transmission's own stretch.
template <class T>
LobeShape<T> transmission_shape(const Lobe& lobe, LobeShape<T> s) {
  const bool own = lobe.transmission_alpha2 > 0.0f;
  s.alpha2 = T(own ? lobe.transmission_alpha2 : lobe.alpha2);
  s.ggx = 1, s.skirt = 1, s.alpha2_hi = 0, s.lmean = 0, s.two_point = false;
  if (own) set_shape_stretch(s, lobe.transmission_stretch, lobe.transmission_stretch_dir);
  if (own && lobe.transmission_alpha2_hi > lobe.transmission_alpha2 * 1.0001f) {
    s.alpha2_hi = T(lobe.transmission_alpha2_hi);
    set_band(s, lobe.transmission_alpha2, lobe.transmission_alpha2_hi, true);
  }
  return s;
}

// A lobe's transmission moments ("Transmission" at the top): the tail coefficient A = E[α²] and the
// peak P = E[1/α²] of its shape, GGX's α² and 1/α², a band's L(l, h) and L/(l·h).
struct TransmissionMoments {
  double tail = 0, peak = 0;
};
inline TransmissionMoments transmission_moments(const Lobe& l) {
  const double lo = l.transmission_alpha2 > 0.0f ? l.transmission_alpha2 : l.alpha2;
  if (!(l.transmission_alpha2 > 0.0f) || !(l.transmission_alpha2_hi > l.transmission_alpha2 * 1.0001f))
    return {lo, 1.0 / lo};
  const double hi = l.transmission_alpha2_hi, L = (hi - lo) / std::log(hi / lo);
  return {L, L / (lo * hi)};
}
// The pair a lobe's transmission reflects: wi (below the geometric surface) mirrored through the plane
// of the lobe's normal n̂, with wo; inv_wi_z is 1/|wi.z|, the f_eff factor's denominator of the
// transmitted direction. Invalid unless wi is below and wo above the geometric surface.
template <class T>
PairTerms<T> transmission_pair(const LobeShape<T>& s, const glm::vec<3, T>& wi, const glm::vec<3, T>& wo) {
  PairTerms<T> p;
  p.wi = wi - (T(2) * glm::dot(s.n, wi)) * s.n;
  p.wo = wo;
  if (!(wi.z < 0) || !(wo.z > 0)) return p;
  p.h = glm::normalize(p.wi + wo);
  p.fresnel_w = schlick_weight(std::min(std::abs(glm::dot(wo, p.h)), T(1)));
  p.inv_wi_z = T(-1) / wi.z;
  p.valid = true;
  return p;
}

// weight · f_eff of one lobe's transmission for wi below and wo above the geometric surface:
//   weight · V·D(wi', wo)·(τ + (τ90 − τ)·w) · E[max(0, n·wi')]·P(n·wo > 0) / |wi.z|,
// wi' the mirror of wi through n̂'s plane (transmission_pair), its sides those of a reflected pair.
// `sides` as lobe_eval's.
template <class T>
glm::vec<3, T> lobe_transmission_eval(const Lobe& lobe, const LobeShape<T>& s_reflected, const glm::vec<3, T>& wi,
                                      const glm::vec<3, T>& wo, T spec_scale = T(1), T* sides = nullptr) {
  using V3 = glm::vec<3, T>;
  if (sides) *sides = 0;
  if (!s_reflected.valid || !transmits(lobe)) return V3(0);
  const LobeShape<T> s = transmission_shape(lobe, s_reflected);
  const PairTerms<T> p = transmission_pair(s, wi, wo);
  if (!p.valid) return V3(0);
  const LobeSide<T> i = lobe_wi_side(s, glm::dot(s.n, p.wi));
  if (!(i.factor > 0)) return V3(0);
  const LobeSide<T> o = lobe_wo_side(s, glm::dot(s.n, p.wo));
  if (!(o.factor > 0)) return V3(0);
  if (sides) *sides = i.factor * o.factor;
  const V3 t(lobe.transmission), t90(lobe.transmission90);
  return (T(lobe.weight) * i.factor * o.factor * p.inv_wi_z * lobe_vd(s, p, i.c, o.c) * spec_scale) *
         (t + (t90 - t) * p.fresnel_w);
}

}  // namespace svbrdf
