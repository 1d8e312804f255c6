#include "appearance/microfacet_normal_mapping.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>

#include "appearance/rng.h"
#include "appearance/shading.h"

// Notation of Schüssler et al. 2017 (the paper): wg the geometric normal (z here), wp the
// perturbed normal with cosθp = <wp, wg> and sinθp its tilt, wt the tangent facet's normal,
// <a, b>⁺ = max(0, a·b). Since wt = −(wp − cosθp wg)/sinθp, wp = cosθp wg − sinθp wt.
//
// Projected areas of the facets per unit geometric area, seen from w (the paper's a_p, a_t):
//   a_p(w) = <w, wp>⁺ / cosθp,   a_t(w) = <w, wt>⁺ sinθp / cosθp.
// For w above the geometric plane a_p(w) + a_t(w) ≥ <w, wg>, with equality when w sees both facets
// (wp + sinθp wt = cosθp wg): the microsurface projects onto the geometric plane exactly. Here
// a_p + a_t appears only multiplied by cosθp, as visible_area(w) = <w, wp>⁺ + sinθp <w, wt>⁺,
// which stays finite and positive for w.z > 0 however small cosθp is.

namespace svbrdf {
namespace {

// The walk needs more random numbers than SampleU holds: a stream seeded from u's bits, so a
// sample stays a function of u (the renderer's sequences stay reproducible).
Rng walk_rng(const SampleU& u) {
  const auto bits = [](float x) { return static_cast<std::uint64_t>(std::bit_cast<std::uint32_t>(x)); };
  return Rng(mix64((bits(u.x) << 32) | bits(u.y)), mix64(bits(u.z) ^ 0x6a09e667f3bcc909ULL));
}

// x kept below p, so a remapped u.x that rounding pushed onto the inner model's split still scatters.
float below(float x, float p) { return std::min(x, std::nextafter(p, 0.0f)); }

// A walk that left through a path eval does not hold (see the header): reported as an impulse.
BsdfSample walk_sample(const glm::vec3& wi, const Rgb& throughput, float choices) {
  BsdfSample s;
  if (!(max_channel(throughput) > 0)) return s;
  s.wi = wi;
  s.pdf = std::max(choices, std::numeric_limits<float>::min());
  s.weight = throughput;
  s.kind = SampleKind::impulse;
  return s;
}

// Up to eight candidate impulses (two inner impulses through four paths); Impulses holds two, the
// strongest are kept and equal directions merge.
struct Candidates {
  std::array<Impulse, 8> items{};
  int count = 0;
  void add(const glm::vec3& d, const Rgb& m) {
    if (!(max_channel(m) > 0)) return;
    for (int i = 0; i < count; ++i) {
      Impulse& it = items[static_cast<std::size_t>(i)];
      if (it.direction == d) {
        it.magnitude += m;
        return;
      }
    }
    if (count < static_cast<int>(items.size())) items[static_cast<std::size_t>(count++)] = {d, m};
  }
  Impulses strongest_two() const {
    int first = -1, second = -1;
    const auto strength = [&](int i) { return max_channel(items[static_cast<std::size_t>(i)].magnitude); };
    for (int i = 0; i < count; ++i) {
      if (first < 0 || strength(i) > strength(first)) {
        second = first;
        first = i;
      } else if (second < 0 || strength(i) > strength(second)) {
        second = i;
      }
    }
    Impulses out;
    for (int i : {first, second})
      if (i >= 0) out.add(items[static_cast<std::size_t>(i)].direction, items[static_cast<std::size_t>(i)].magnitude);
    return out;
  }
};

}  // namespace

MicrofacetNormalMapping::MicrofacetNormalMapping(const Bsdf& inner, const glm::vec3& wp) : inner_(inner) {
  const float len = glm::length(wp);
  if (!(len > 0) || !std::isfinite(len)) return;  // no normal: shade about wg
  glm::vec3 n = wp / len;
  const float tilt = std::sqrt(n.x * n.x + n.y * n.y);
  if (!(tilt > 0)) return;  // wp = wg (or −wg, which has no tilt direction to clamp along)
  // wt: perpendicular to wg, in the plane of wg and wp, on the side away from wp's tilt.
  wt_ = glm::vec3(-n.x / tilt, -n.y / tilt, 0.0f);
  cos_p_ = n.z;
  sin_p_ = tilt;
  if (!(cos_p_ >= kMinCosWp)) {
    // The microsurface needs <wp, wg> > 0 (a height field); near 0 it degenerates into vertical
    // facets. Turn wp toward wg in the plane of both.
    cos_p_ = kMinCosWp;
    sin_p_ = std::sqrt(1.0f - kMinCosWp * kMinCosWp);
    n = glm::vec3(0.0f, 0.0f, cos_p_) - sin_p_ * wt_;
  }
  frame_p_ = Frame::from_normal_tangent(n, {1.0f, 0.0f, 0.0f});
  pass_through_ = false;
}

// w mirrored in the plane of wt: a ray travelling along w leaves the mirror facet wt travelling
// along mirror_t(w) (the paper's reflection on wt). It keeps w.z: a ray that meets wt going down
// still goes down after it.
glm::vec3 MicrofacetNormalMapping::mirror_t(const glm::vec3& w) const { return w - 2.0f * glm::dot(w, wt_) * wt_; }

// The paper's intersection probability λp(w) = a_p(w) / (a_p(w) + a_t(w)): the probability that a
// ray arriving from w meets wp first (λt = 1 − λp: wt first). The 1/cosθp cancels.
float MicrofacetNormalMapping::lambda_p(const glm::vec3& w) const {
  const float den = visible_area(w);
  return den > 0 ? std::max(0.0f, glm::dot(w, frame_p_.n)) / den : 1.0f;
}

// cosθp (a_p(w) + a_t(w)) = <w, wp>⁺ + sinθp <w, wt>⁺.
float MicrofacetNormalMapping::visible_area(const glm::vec3& w) const {
  return std::max(0.0f, glm::dot(w, frame_p_.n)) + sin_p_ * std::max(0.0f, glm::dot(w, wt_));
}

// The paper's masking (and shadowing) function of a facet wm ∈ {wp, wt}:
//   G1(w, wm) = χ⁺(<w, wm>) · min(1, <w, wg>⁺ / (a_p(w) + a_t(w))),
// the probability that a ray leaving facet wm along w leaves the microsurface; otherwise it meets
// the other facet (a ray leaving one facet can only meet the other). With the visible area:
//   <w, wg> / (a_p + a_t) = <w, wg> cosθp / visible_area(w).
float MicrofacetNormalMapping::masking(const glm::vec3& w, const glm::vec3& wm) const {
  if (!(w.z > 0) || !(glm::dot(w, wm) > 0)) return 0.0f;
  const float den = visible_area(w);
  return den > 0 ? std::min(1.0f, w.z * cos_p_ / den) : 0.0f;
}

// G1(w, wm) / <w, wg>, finite at grazing w: min(1/<w, wg>, cosθp / visible_area(w)).
float MicrofacetNormalMapping::masking_over_cos(const glm::vec3& w, const glm::vec3& wm) const {
  if (!(w.z > 0) || !(glm::dot(w, wm) > 0)) return 0.0f;
  const float den = visible_area(w);
  return den > 0 ? std::min(1.0f / w.z, cos_p_ / den) : 0.0f;
}

// For the path wo → wp → wt → wi: with wi' = mirror_t(wi) (the direction in which wp sends the light
// that wt then mirrors to wi), the paper's <wi', wp> (1 − G1(wi', wp)). When <wi, wt> > 0, wi' sees
// only wp, so G1(wi', wp) = cosθp <wi, wg> / <wi', wp> and <wi', wp> = cosθp <wi, wg> + sinθp <wi, wt>:
// the product is sinθp <wi, wt>, computed without the cancellation of 1 − G1.
float MicrofacetNormalMapping::blocked_cos(const glm::vec3& wi) const {
  return sin_p_ * std::max(0.0f, glm::dot(wi, wt_));
}

// The explicit evaluation, f(wi, wo) <wi, wg> as a sum over the four paths with one scattering on wp
// (fp the inner BSDF in the frame of wp, wo' = mirror_t(wo), wi' = mirror_t(wi)):
//   wo → wp → wi:            λp(wo) fp(wi, wo)   <wi, wp>  G1(wi, wp)
//   wo → wp → wt → wi:       λp(wo) fp(wi', wo)  <wi', wp> (1 − G1(wi', wp)) G1(wi, wt)
//   wo → wt → wp → wi:       λt(wo) fp(wi, wo')  <wi, wp>  G1(wi, wp)
//   wo → wt → wp → wt → wi:  λt(wo) fp(wi', wo') <wi', wp> (1 − G1(wi', wp)) G1(wi, wt)
// The first three are the paper's; the fourth is as exact: a ray that wt mirrors descends and meets
// wp for sure (the paper's 1 − G1(wo', wt) = 1), and it leaves wp along wi' as in the second. Without
// it a viewer that sees only wt (λp = 0) gets nothing from a light that sees only wt (<wi, wp> ≤ 0):
// black under a delta light, which reaches the microsurface through eval alone. The four are
// reciprocal as a set (the second and third exchange under wi ↔ wo; the first and fourth are their
// own images).
Rgb MicrofacetNormalMapping::eval(const glm::vec3& wi, const glm::vec3& wo) const {
  if (pass_through_) return inner_.eval(wi, wo);
  if (!(wi.z > 0) || !(wo.z > 0)) return Rgb(0.0f);
  const glm::vec3& wp = frame_p_.n;
  const float lp = lambda_p(wo), lt = 1.0f - lp;
  const float direct = masking_over_cos(wi, wp);    // G1(wi, wp) / <wi, wg>
  const float escape_t = masking_over_cos(wi, wt_);  // G1(wi, wt) / <wi, wg>
  const glm::vec3 wi_p = to_p(wi), wi_mp = to_p(mirror_t(wi));
  Rgb f(0.0f);
  // The light leaves wp toward the viewer along `toward` (wo, or wo' after wt), first facet chosen with l.
  const auto through_wp = [&](const glm::vec3& toward, float l) {
    const glm::vec3 toward_p = to_p(toward);
    if (direct > 0) f += inner_.eval(wi_p, toward_p) * (l * glm::dot(wi, wp) * direct);
    if (escape_t > 0) f += inner_.eval(wi_mp, toward_p) * (l * blocked_cos(wi) * escape_t);
  };
  if (lp > 0) through_wp(wo, lp);
  if (lt > 0) through_wp(mirror_t(wo), lt);
  return f;
}

// The density of the walks that take the four explicit paths through a finite inner sample: the
// facet is chosen with λ, the inner model samples with its pdf, leaving or meeting the other facet
// is chosen with G1; mirroring is a one-to-one map of directions of Jacobian 1.
float MicrofacetNormalMapping::pdf(const glm::vec3& wi, const glm::vec3& wo) const {
  if (pass_through_) return inner_.pdf(wi, wo);
  if (!(wi.z > 0) || !(wo.z > 0)) return 0.0f;
  const glm::vec3& wp = frame_p_.n;
  const float lp = lambda_p(wo), lt = 1.0f - lp;
  const float direct = masking(wi, wp);
  const float escape_t = masking(wi, wt_);
  const glm::vec3 wi_m = mirror_t(wi);
  const glm::vec3 wi_p = to_p(wi), wi_mp = to_p(wi_m);
  // (1 − G1(wi', wp)) G1(wi, wt)
  const float via_t = escape_t > 0 ? blocked_cos(wi) / glm::dot(wi_m, wp) * escape_t : 0.0f;
  float p = 0.0f;
  const auto through_wp = [&](const glm::vec3& toward, float l) {
    const glm::vec3 toward_p = to_p(toward);
    if (direct > 0) p += l * inner_.pdf(wi_p, toward_p) * direct;
    if (via_t > 0) p += l * inner_.pdf(wi_mp, toward_p) * via_t;
  };
  if (lp > 0) through_wp(wo, lp);
  if (lt > 0) through_wp(mirror_t(wo), lt);
  return p;
}

float MicrofacetNormalMapping::scatter_probability(const glm::vec3& wo) const {
  if (pass_through_) return inner_.scatter_probability(wo);
  if (!(wo.z > 0)) return 0.0f;
  const float lp = lambda_p(wo), lt = 1.0f - lp;
  float p = 0.0f;
  if (lp > 0) p += lp * inner_.scatter_probability(to_p(wo));
  if (lt > 0) p += lt * inner_.scatter_probability(to_p(mirror_t(wo)));
  return p;
}

// The paper's random walk on the microsurface, from the viewer's side (see the header for what is
// returned). `toward` is the direction, as the next wp event sees it, in which the light leaves wp
// toward the viewer: the inner model's wo.
BsdfSample MicrofacetNormalMapping::sample(const glm::vec3& wo, const SampleU& u) const {
  if (pass_through_) return inner_.sample(wo, u);
  if (!(wo.z > 0)) return {};
  const glm::vec3& wp = frame_p_.n;
  const float lp = lambda_p(wo), lt = 1.0f - lp;
  const glm::vec3 wo_t = mirror_t(wo);
  const float pp = lp > 0 ? inner_.scatter_probability(to_p(wo)) : 0.0f;
  const float pt = lt > 0 ? inner_.scatter_probability(to_p(wo_t)) : 0.0f;
  // First event: u.x picks the facet with λ and the inner model's energy split in one go, so that
  // the walk is absorbed exactly when u.x ≥ scatter_probability(wo) (bsdf.h).
  bool first_on_t = false;
  float ux = 0.0f;
  if (u.x < lp * pp) {
    ux = below(u.x / lp, pp);
  } else if (u.x < lp * pp + lt * pt) {
    first_on_t = true;  // the ray meets wt, is mirrored, descends onto wp
    ux = below((u.x - lp * pp) / lt, pt);
  } else {
    return {};
  }

  Rng rng = walk_rng(u);
  Rgb throughput(1.0f);
  float choices = first_on_t ? lt : lp;
  glm::vec3 toward = first_on_t ? wo_t : wo;
  SampleU v{ux, u.y, u.z};
  for (int event = 1; event <= kMaxWpEvents; ++event) {
    const BsdfSample s = inner_.sample(to_p(toward), v);
    if (s.kind == SampleKind::absorbed) return {};
    throughput *= s.weight;
    if (s.kind == SampleKind::impulse) choices *= s.pdf;
    const bool explicit_path = event == 1 && s.kind == SampleKind::finite;
    glm::vec3 d = from_p(s.wi);
    if (!(s.wi.z > 0)) return walk_sample(d, throughput, choices);  // transmitted below wp
    const float g = masking(d, wp);
    if (rng.next_float() < g) {
      // wo → wp → wi or wo → wt → wp → wi
      if (explicit_path) return finite_sample(d, pdf(d, wo), eval(d, wo));
      return walk_sample(d, throughput, choices * g);
    }
    choices *= 1.0f - g;
    d = mirror_t(d);  // met wt
    const float gt = masking(d, wt_);
    if (rng.next_float() < gt) {
      // wo → wp → wt → wi or wo → wt → wp → wt → wi
      if (explicit_path) return finite_sample(d, pdf(d, wo), eval(d, wo));
      return walk_sample(d, throughput, choices * gt);
    }
    choices *= 1.0f - gt;
    toward = -d;
    v = SampleU{rng.next_float(), rng.next_float(), rng.next_float()};
  }
  return {};  // cut by the bound
}

// The inner model's impulses through the four explicit paths, with eval's factors; an impulse
// below wp's plane (transmission) is passed through with the facet's λ and no masking.
Impulses MicrofacetNormalMapping::impulses_in(const glm::vec3& wo) const {
  if (pass_through_) return inner_.impulses_in(wo);
  if (!(wo.z > 0)) return {};
  const glm::vec3& wp = frame_p_.n;
  const float lp = lambda_p(wo), lt = 1.0f - lp;
  Candidates c;
  const auto through_wp = [&](const glm::vec3& toward, float l) {
    const Impulses in = inner_.impulses_in(to_p(toward));
    for (int i = 0; i < in.count; ++i) {
      const Impulse& imp = in.items[static_cast<std::size_t>(i)];
      const glm::vec3 d = from_p(imp.direction);
      if (!(imp.direction.z > 0)) {
        c.add(d, l * imp.magnitude);
        continue;
      }
      const float g = masking(d, wp);
      c.add(d, (l * g) * imp.magnitude);  // wo → wp → wi, wo → wt → wp → wi
      const glm::vec3 wi = mirror_t(d);
      // wo → wp → wt → wi, wo → wt → wp → wt → wi
      c.add(wi, (l * (1.0f - g) * masking(wi, wt_)) * imp.magnitude);
    }
  };
  if (lp > 0) through_wp(wo, lp);
  if (lt > 0) through_wp(mirror_t(wo), lt);
  return c.strongest_two();
}

// The same four paths seen from the light: light from wi reaches wp directly (G1(wi, wp)) or
// after wt (wi' = mirror_t(wi), 1 − G1(wi', wp), G1(wi, wt)); the inner model's impulse leaves wp
// along e, toward a viewer at e (λp(e)) or, mirrored by wt, at mirror_t(e) (λt).
Impulses MicrofacetNormalMapping::impulses_out(const glm::vec3& wi) const {
  if (pass_through_) return inner_.impulses_out(wi);
  if (!(wi.z > 0)) return {};
  const glm::vec3& wp = frame_p_.n;
  Candidates c;
  const auto leave = [&](const Impulses& out, float arrive) {
    for (int i = 0; i < out.count; ++i) {
      const Impulse& imp = out.items[static_cast<std::size_t>(i)];
      const glm::vec3 e = from_p(imp.direction);
      if (!(imp.direction.z > 0)) {
        c.add(e, arrive * imp.magnitude);  // transmitted below wp
        continue;
      }
      if (!(e.z > 0)) continue;  // descends onto wt and wp again: the walk's
      c.add(e, (arrive * lambda_p(e)) * imp.magnitude);  // wi → wp → wo or wi → wt → wp → wo
      const glm::vec3 wo = mirror_t(e);
      // wi → wp → wt → wo, wi → wt → wp → wt → wo
      c.add(wo, (arrive * (1.0f - lambda_p(wo))) * imp.magnitude);
    }
  };
  const float direct = masking(wi, wp);
  if (direct > 0) leave(inner_.impulses_out(to_p(wi)), direct);
  const float escape_t = masking(wi, wt_);
  if (escape_t > 0) {
    const glm::vec3 wi_m = mirror_t(wi);
    const float blocked = blocked_cos(wi) / glm::dot(wi_m, wp);
    leave(inner_.impulses_out(to_p(wi_m)), blocked * escape_t);
  }
  return c.strongest_two();
}

}  // namespace svbrdf
