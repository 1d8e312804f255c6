#pragma once
// The clear coat of a BRDF texel (KHR_materials_clearcoat) and the effective BRDF f_eff of
// ../shared/spec/brdf-mip.md for a coated texel, in the lobes of lobe.h.
//
// The extension layers the coat over the whole material (its fresnel_coat, with the coat's ior 1.5):
//   f = (1 − c·Fc)·f_base + c·Fc·D_c·V_c,   Fc = 0.04 + 0.96·(1 − |wo·Nc|)^5,
// with c the clearcoat weight, D_c and V_c GGX and its height-correlated Smith visibility at the coat's
// α_c = max(clearcoatRoughness², 1e-3) about the coat's normal Nc (V_c·D_c vanishes where Nc faces
// away from either direction). Fc is taken at the view's cosine to Nc, not at wo·h: the extension's
// text, which the renderer follows (appearance/gltf_surface_bsdf.h). The renderer shades the whole
// layered BSDF in the frame of the base's shading normal n_x: it vanishes where n_x faces away from
// either direction, and its cosine factor is n_x's. So a level-0 texel reflects
//   f_eff = (1 − c·Fc)·f_eff,base + c·Fc·D_c·V_c·max(0, n_x·wi)·[n_x·wo > 0]/wi.z.
//
// A coarse texel's mixture carries, beside its base lobes (lobe.h),
//   the coat lobes — Lobes with F0 = 0.04, F90 = 1 and no diffuse term, whose weight is the texels'
//     mean clearcoat, normal the mean of the coat normals (unnormalized), shape the coat roughness
//     reduced as the base lobes are (lobe_reduction.h); their Schlick weight is taken at wo·n̂ of the
//     lobe's own mean coat normal n̂ (coat_pair below), which is Fc exactly for one texel, and their
//     own horizons are the facing probabilities of lobe.h's spread normals;
//   each base lobe's coat — the mean clearcoat of the texels it stands for (Lobe::coat), averaged by
//     merges as F0 is.
// The base lobe k is attenuated by
//   1 − coat_k·F̄(wo),  F̄(wo) = Σ_j w_j·Fc_j(wo) / Σ_j w_j       (j over the coat lobes, Fc_j at n̂_j).
// Why: the exact coarse texel's attenuation term is mean_x[c_x·Fc_x(wo)·f_eff,base,x]. Where the coat
// normals do not vary with the base (F̄ the same for every texel), it is F̄·mean_x[c_x·f_eff,base,x], and
// the base lobes carry mean_x[c_x·f_x] exactly as long as their merges keep apart texels of different
// clearcoat (each lobe's share of it is linear in its texels); one c̄ per texel instead assumes c_x
// uncorrelated with f_x and measured 2-3 % of flux off where a coat map follows the base's
// (bench/results/mip.md). At level 0 it is c·Fc exactly.
// The coat term's cosine factor and horizons, mean_x c_x·max(0, n_x·wi)·[n_x·wo > 0] / mean_x c_x, are
// the base's: each base lobe already stands for its texels' normals (lobe.h's clipped cosine and facing
// probability about its mean normal) and their clearcoat, so the coat term takes
//   K(wi, wo) = Σ_k w_k·coat_k·E_k[max(0, n·wi)]·P_k(n·wo > 0) / Σ_k w_k·coat_k   (k over the base lobes),
// the base lobes' weights standing for their area shares (a merge's flux rescaling moves them by a few
// percent at most). One Gaussian of normals about the texel's mean normal would carry no more than
// that, and measured worse: a glossy coat over a bumped base concentrates the metric on the mirror
// pairs of grazing directions, where the spread of the base's normals decides the factor
// (bench/results/mip.md). At level 0 K is exactly max(0, n_x·wi)·[n_x·wo > 0].
#include <algorithm>
#include <array>
#include <span>

#include <glm/glm.hpp>

#include "appearance/gltf.h"
#include "mip/lobe.h"
#include "textures/material_texels.h"

namespace svbrdf {

// KHR_materials_clearcoat fixes the coat's ior at 1.5: F0 = ((1.5 − 1)/(1.5 + 1))².
inline constexpr float kCoatF0 = 0.04f;

// The level-0 coat lobe of a texel (weight = its clearcoat times `share`, its area share).
inline Lobe coat_lobe(const CoatLayer& coat, float share = 1.0f) {
  const float alpha = gltf_alpha(std::clamp(coat.roughness, 0.0f, 1.0f));
  Lobe l;
  l.weight = std::clamp(coat.weight, 0.0f, 1.0f) * share;
  l.diffuse = glm::vec3(0.0f);
  l.f0 = glm::vec3(kCoatF0);
  l.f0_tint = glm::vec3(0.0f);
  l.normal = coat.normal;
  l.alpha2 = alpha * alpha;
  return l;
}

// What a texel's mixture holds of its coat beside its base lobes' shares: its coat lobes (none: no coat).
struct CoatTexel {
  std::span<const Lobe> lobes;
  bool present() const { return !lobes.empty(); }
};

// The pair terms of a coat lobe about its mean normal n̂: Schlick's weight at |wo·n̂| (Fc's), the rest
// the pair's.
template <class T>
PairTerms<T> coat_pair(const PairTerms<T>& p, const glm::vec<3, T>& n) {
  PairTerms<T> q = p;
  q.fresnel_w = schlick_weight(std::min(std::abs(glm::dot(p.wo, n)), T(1)));
  return q;
}

// weight · c·Fc·V·D of one coat lobe for a pair, about its own normal (its shape s), times the share of
// its texels whose coat normal faces both directions; without the base's cosine factor K. `fresnel_w`,
// when the caller has it (CoatFresnel::add returns it), is Schlick's weight at |wo·n̂|.
template <class T>
glm::vec<3, T> coat_lobe_eval(const Lobe& coat, const LobeShape<T>& s, const PairTerms<T>& p, T fresnel_w = T(-1)) {
  using V3 = glm::vec<3, T>;
  if (!p.valid || !s.valid) return V3(0);
  const LobeSide<T> ci = lobe_wo_side(s, glm::dot(s.n, p.wi));
  if (!(ci.factor > 0)) return V3(0);
  const LobeSide<T> co = lobe_wo_side(s, glm::dot(s.n, p.wo));
  if (!(co.factor > 0)) return V3(0);
  PairTerms<T> q = p;
  q.fresnel_w = fresnel_w >= 0 ? fresnel_w : coat_pair(p, s.n).fresnel_w;
  return (T(coat.weight) * ci.factor * co.factor) * lobe_brdf(coat, s, q, ci.c, co.c);
}

// K(wi, wo)/wi.z (the top of this file), summed one base lobe at a time (each with its shape): 0 where no
// base lobe has a coat.
template <class T>
struct CoatCosine {
  T num = 0, den = 0;
  void add(const Lobe& l, const LobeShape<T>& s, const PairTerms<T>& p) {
    const T share = T(l.weight) * T(l.coat);
    if (!s.valid || !(share > 0)) return;
    den += share;
    const LobeSide<T> i = lobe_wi_side(s, glm::dot(s.n, p.wi));
    if (!(i.factor > 0)) return;
    const LobeSide<T> o = lobe_wo_side(s, glm::dot(s.n, p.wo));
    num += share * i.factor * o.factor;
  }
  // The same, given the product of the lobe's two sides' factors that lobe_eval reported (lobe.h).
  void add_sides(const Lobe& l, const LobeShape<T>& s, T sides) {
    const T share = T(l.weight) * T(l.coat);
    if (!s.valid || !(share > 0)) return;
    den += share;
    num += share * sides;
  }
  T value(const PairTerms<T>& p) const { return den > 0 ? num / den * p.inv_wi_z : T(0); }
};

// The same of a texel's base lobes, given their shapes.
template <class T>
T coat_cosine(std::span<const Lobe> base, const LobeShape<T>* shapes, const PairTerms<T>& p) {
  if (!p.valid) return T(0);
  CoatCosine<T> k;
  for (std::size_t i = 0; i < base.size(); ++i) k.add(base[i], shapes[i], p);
  return k.value(p);
}

// F̄(wo), the coat lobes' mean Fresnel weight toward wo (the top of this file), summed one coat lobe at
// a time.
template <class T>
struct CoatFresnel {
  T num = 0, den = 0;
  void add(const Lobe& l, const glm::vec<3, T>& wo) {
    const glm::vec<3, T> n(l.normal);
    const T len = glm::length(n);
    if (!(l.weight > 0) || !(len > 0)) return;
    const T w = schlick_weight(std::min(std::abs(glm::dot(wo, n)) / len, T(1)));
    num += T(l.weight) * (T(kCoatF0) + (T(1) - T(kCoatF0)) * w);
    den += T(l.weight);
  }
  // The same given the lobe's shape (its unit normal n̂); returns Schlick's weight at |wo·n̂|, which the
  // lobe's own term takes too (coat_lobe_eval), or −1 where the lobe has no shape.
  T add(const Lobe& l, const LobeShape<T>& s, const glm::vec<3, T>& wo) {
    if (!s.valid) return T(-1);
    const T w = schlick_weight(std::min(std::abs(glm::dot(wo, s.n)), T(1)));
    num += T(l.weight) * (T(kCoatF0) + (T(1) - T(kCoatF0)) * w);
    den += T(l.weight);
    return w;
  }
  T value() const { return den > 0 ? num / den : T(0); }
};

// The same of a texel's coat.
template <class T>
T coat_fresnel(const CoatTexel& coat, const glm::vec<3, T>& wo) {
  CoatFresnel<T> f;
  for (const Lobe& l : coat.lobes) f.add(l, wo);
  return f.value();
}

// f_eff of a coated texel for a pair, given its base lobes, their sum there (`base`, lobe_eval of each)
// and the same sum weighted by each lobe's coat (`base_coated`).
template <class T>
glm::vec<3, T> coated_eval(const glm::vec<3, T>& base, const glm::vec<3, T>& base_coated, std::span<const Lobe> base_lobes,
                           const CoatTexel& coat, const PairTerms<T>& p) {
  if (!coat.present() || !p.valid) return base;
  std::array<LobeShape<T>, 8> shapes;  // kMaxLobes (lobe_reduction.h)
  const std::size_t n = std::min<std::size_t>(base_lobes.size(), shapes.size());
  for (std::size_t k = 0; k < n; ++k) shapes[k] = lobe_shape<T>(base_lobes[k], false);
  const T cosine = coat_cosine(base_lobes.first(n), shapes.data(), p);
  glm::vec<3, T> c(0);
  if (cosine > 0)
    for (const Lobe& l : coat.lobes) c += coat_lobe_eval(l, lobe_shape<T>(l), p);
  return base - coat_fresnel(coat, p.wo) * base_coated + cosine * c;
}

// A level-0 texel's coat: its one coat lobe (made into `scratch`).
inline CoatTexel level0_coat(const CoatLayer& layer, Lobe& scratch) {
  scratch = coat_lobe(layer);
  if (!(scratch.weight > 0)) return {};
  return {{&scratch, 1}};
}

// table += scale · (base − F̄(wo)·base_coated + K·the coat's terms) over the direction grid's pairs
// (direction_grid.h), `base` the sum of the texel's base lobes over the same pairs and `base_coated` the
// same weighted by each lobe's coat; the coat evaluated in precision T (double: the exact reference's;
// float: the renderer's).
template <class T>
void accumulate_coat(std::span<const Lobe> base_lobes, const CoatTexel& coat, std::span<const glm::dvec3> base,
                     std::span<const glm::dvec3> base_coated, double scale, std::span<glm::dvec3> table);

// table += scale · f_eff of a coated texel over the direction grid's pairs, in double precision: the
// exact reference's.
void accumulate_coated_double(std::span<const Lobe> base, const CoatTexel& coat, double scale, std::span<glm::dvec3> table);

}  // namespace svbrdf
