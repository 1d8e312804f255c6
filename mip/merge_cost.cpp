#include "mip/merge_cost.h"

#include <algorithm>
#include <cmath>

#include "mip/reduction_numerics.h"

namespace svbrdf::reduction {

namespace {

// D at h = z (the geometric normal) of a lobe.
double d_at_z(const LobeShape<double>& sh) {
  if (!sh.valid) return 0.0;
  return d_at_tan2(DShape::of(sh), tan2_between(sh.n, glm::dvec3(0, 0, 1)));
}

}  // namespace

void profile_of(const DShape& sh, std::array<double, kProfileSteps>& out) {
  struct Steps {
    std::array<double, kProfileSteps> t{}, q{};  // tan²θ and d_at_tan2's (1 + t)²/π
  };
  static const Steps steps = [] {
    Steps s;
    for (std::size_t j = 0; j < kProfileSteps; ++j) {
      s.t[j] = profile_step(j);
      s.q[j] = (1 + s.t[j]) * (1 + s.t[j]) / kPiD;
    }
    return s;
  }();
  const double a2 = sh.alpha2;
  if (sh.alpha2_hi > 0) {
    const double hi = sh.alpha2_hi, atom = (1.0 - sh.ggx) * a2;
    if (sh.two_point) {
      const double c = sh.ggx * hi;
      for (std::size_t j = 0; j < kProfileSteps; ++j) out[j] = c / ((steps.t[j] + hi) * (steps.t[j] + hi));
    } else {
      const double c = sh.ggx * sh.lmean;
      for (std::size_t j = 0; j < kProfileSteps; ++j) out[j] = c / ((steps.t[j] + a2) * (steps.t[j] + hi));
    }
    for (std::size_t j = 0; j < kProfileSteps; ++j) out[j] = steps.q[j] * (out[j] + atom / ((steps.t[j] + a2) * (steps.t[j] + a2)));
    return;
  }
  {
    const double c = sh.ggx * a2;
    for (std::size_t j = 0; j < kProfileSteps; ++j) out[j] = c / ((steps.t[j] + a2) * (steps.t[j] + a2));
  }
  if (sh.ggx != 1.0) {
    const double b2 = a2 * sh.skirt;
    for (std::size_t j = 0; j < kProfileSteps; ++j) {
      const double x = steps.t[j] / b2;
      if (x < 60.0) out[j] += (1.0 - sh.ggx) * double(series_exp(static_cast<float>(-x))) / b2;
    }
  }
  for (std::size_t j = 0; j < kProfileSteps; ++j) out[j] = steps.q[j] * out[j];
}

Summary summarize(const Lobe& l) {
  Summary s;
  const glm::dvec3 nbar(l.normal);
  const double len = glm::length(nbar);
  s.n = len > 0 ? nbar / len : glm::dvec3(0, 0, 1);
  s.weight = l.weight;
  s.rho = mean3(l.diffuse);
  s.f0 = mean3(l.f0);
  s.f90 = l.f90;
  s.amp = specular_amp(l.weight, len, s.f0, s.f90);
  const LobeShape<double> sh = lobe_shape<double>(l, false);
  s.ggx = sh.ggx;
  if (sh.alpha2_hi > 0) {
    // A roughness mixture: its atom at l (share 1 − β) and its upper part (lobe.h). The width term of
    // union_cost takes it as one GGX core (μ = 1).
    const double beta = sh.ggx, l = sh.alpha2, h = sh.alpha2_hi;
    s.tail = beta * (sh.two_point ? h : sh.lmean) + (1 - beta) * l;
    s.peak = beta * (sh.two_point ? 1 / h : sh.lmean / (l * h)) + (1 - beta) / l;
    s.ggx = 1;
  } else {
    s.tail = s.ggx * sh.alpha2;
    s.peak = (s.ggx + (1 - s.ggx) / sh.skirt) / sh.alpha2;
  }
  s.alpha2 = 1 / s.peak;
  s.d_shape = DShape::of(sh);
  s.d_z = d_at_z(sh);
  profile_of(s.d_shape, s.profile);
  // The slope of every lobe's normal, not only a stretched one's: an isotropic lobe in a union with a
  // stretched one is offset from the merged normal by it (lobe_reduction.cpp, merge_union).
  s.slope = normal_slope(s.n);
  if (sh.stretched) {
    s.stretched = true;
    s.stretch = stretch_matrix(l);
    s.stretch_log = stretch_log(l);
  }
  if (transmits(l)) {
    s.trans = (l.weight * len) * (glm::dvec3(l.transmission) + 0.05 * (glm::dvec3(l.transmission90) - glm::dvec3(l.transmission)));
    const TransmissionMoments tm = transmission_moments(l);
    s.alpha2_t = 1.0 / tm.peak;
    s.tail_t = tm.tail;
    profile_of(DShape::of(transmission_shape(l, sh)), s.trans_profile);
  }
  return s;
}

namespace {
// ln(a/b)², a, b > 0. ln(a/b) = 2·atanh(q), q = (a − b)/(a + b): for the near matches that decide merges
// (|q| < ½, a ratio within 3) the series to q⁹ (within 4e-5) in one division.
double log_ratio2(double a, double b) {
  const double q = (a - b) / (a + b), q2 = q * q;
  const double r = q2 < 0.25 ? 2 * q * (1 + q2 * (1.0 / 3 + q2 * (1.0 / 5 + q2 * (1.0 / 7 + q2 * (1.0 / 9)))))
                             : series_log(a / b);
  return r * r;
}

// The width term's norm: a change Δ of a tail coefficient changes D by Δ/(π·t²) far out, whose squared
// L2 over slope space from the resolution outward is Δ²/(3π·α⁶_res) (union_cost).
constexpr double kWidthNorm = 3 * kPiD * kResolutionAlpha2 * kResolutionAlpha2 * kResolutionAlpha2;

// Σ_i (trans_i·t/3)·⟨T_i, T(alpha2)⟩ over the union: its transmission's inner product with a lobe of
// amplitude t and α²_T alpha2.
double trans_cross(std::span<const Member> u, const glm::dvec3& t, double alpha2) {
  double s = 0;
  for (const Member& x : u)
    if (has_transmission(*x.sum)) s += glm::dot(x.sum->trans, t) / 3 * trans_inner(x.sum->alpha2_t, alpha2);
  return s;
}
}  // namespace

double union_trans_norm2(std::span<const Member> u) {
  double s = 0;
  for (std::size_t i = 0; i < u.size(); ++i)
    if (has_transmission(*u[i].sum)) s += trans_cross(u, u[i].sum->trans, u[i].sum->alpha2_t);
  return s;
}

namespace {
// union_cost's terms for the union's transmission (merge_cost.h), the merged lobe m's amplitude the
// union's (the merge keeps its flux), 0 where no member transmits: per channel c, with t the members'
// amplitudes,
//   the L2 error       Σ_ij t_i·t_j·⟨T_i, T_j⟩ − 2·Σ_i t_i·T_m·⟨T_i, T_m⟩ + T_m²·⟨T_m, T_m⟩,
//   the peak           Σ t_i·P_i/π − T_m·P_m/π, weighted as the reflection's,
//   the core widths    Σ t_i·A_i − T_m·A_m (the tail coefficients),
//   the log profile    of Σ t_i·D_i against T_m·D_m, weighted as the reflection's by T_m², its mean
//                      over the steps at and above the resolution (tan²θ ≥ α²_res);
// averaged over the channels. The profile's steps below the resolution are left out: every transmission
// lobe, the merged one too, is centred on the one straight-through direction, so what lies within α_res
// of it is a single peak, which the cost model sees, as it sees every lobe, blurred to α²_res — by its
// height (the peak term, P, which the merge keeps) and its flux (which the merge keeps) — and not by its
// shape. The reflection's profile keeps them: its lobes' peaks lie about their own normals, apart. With
// them, the cost spent lobes on sub-resolution transmission shapes that the reflection then lacked
// (docs/mip-algorithm.md §4.6 has the figures).
double trans_cost(std::span<const Member> u, const UnionTerms& t, const Summary& m, double peak_weight) {
  if (!(t.trans_self > 0)) return 0.0;
  glm::dvec3 Tm(0.0), peak(0.0), width(0.0);
  for (const Member& x : u) {
    const Summary& a = *x.sum;
    if (!has_transmission(a)) continue;
    Tm += a.trans;
    peak += a.trans / (kPiD * a.alpha2_t);
    width += a.trans * a.tail_t;
  }
  peak -= Tm / (kPiD * m.alpha2_t);
  width -= Tm * m.tail_t;
  const double l2 = std::max(0.0, t.trans_self - 2 * trans_cross(u, Tm, m.alpha2_t) +
                                      glm::dot(Tm, Tm) / 3 * trans_inner(m.alpha2_t, m.alpha2_t));
  double profile = 0;
  for (int c = 0; c < 3; ++c) {
    if (!(Tm[c] > 0)) continue;
    double e = 0;
    for (std::size_t j = kResolvedProfileStep; j < kProfileSteps; ++j) {
      double ex = 0;
      for (const Member& x : u) ex += x.sum->trans[c] * x.sum->trans_profile[j];
      const double ap = Tm[c] * m.trans_profile[j];
      if (ex > 0 && ap > 0) e += log_ratio2(ap, ex);
    }
    profile += Tm[c] * Tm[c] * e;
  }
  return l2 + (peak_weight * glm::dot(peak, peak) + glm::dot(width, width) / kWidthNorm +
               kProfileWeight * profile / (kProfileSteps - kResolvedProfileStep)) / 3;
}
}  // namespace

double union_spec_norm2(std::span<const Member> u) {
  double s = 0;
  for (std::size_t i = 0; i < u.size(); ++i) {
    const Summary& a = *u[i].sum;
    s += a.amp * a.amp * spec_inner(a, a, 0);
    for (std::size_t j = i + 1; j < u.size(); ++j) {
      const Summary& b = *u[j].sum;
      s += 2 * a.amp * b.amp * spec_inner(a, b, tan2_between(a.n, b.n));
    }
  }
  return s;
}

HorizonSums horizon_sums(std::span<const Member> u, double W) {
  HorizonSums h;
  const double inv_w = 1.0 / W;
  for (std::size_t i = 0; i < u.size(); ++i)
    for (std::size_t j = i + 1; j < u.size(); ++j) {
      const Summary &a = *u[i].sum, &b = *u[j].sum;
      const double ab = a.weight * b.weight * inv_w;
      const double cos_ab = std::clamp(glm::dot(a.n, b.n), -1.0, 1.0);
      const glm::dvec3 d = a.n - b.n;
      const double delta = std::sqrt(glm::dot(d, d));  // the angle between the normals, to O(δ³)
      const double drho = a.rho - b.rho;
      h.lune += ab * delta;
      h.coupling += (8.0 / 3.0) * ab * ab * drho * drho * (1.0 - cos_ab);
    }
  return h;
}

double union_weight(std::span<const Member> u) {
  double W = 0;
  for (const Member& x : u) W += x.sum->weight;
  return W;
}

double union_cost_bound(std::span<const Member> u, const HorizonSums& h) {
  double W = 0, rho = 0, f0 = 0;
  for (const Member& x : u) W += x.sum->weight, rho += x.sum->weight * x.sum->rho, f0 += x.sum->weight * x.sum->f0;
  return (1.0 - 1e-6) * h.cost(rho / W, f0 / W);
}

double union_cost(std::span<const Member> u, const UnionTerms& t, const Summary& m, bool by_amp, double peak_weight) {
  double Am = 0, peak = 0, width = 0, spec = t.self, W = 0;
  for (const Member& x : u) Am += x.sum->amp, W += x.sum->weight;
  spec += Am * Am * spec_inner(m, m, 0);
  for (const Member& x : u) {
    const Summary& a = *x.sum;
    spec -= 2 * Am * a.amp * spec_inner(m, a, tan2_between(a.n, m.n));
    peak += a.amp * a.d_z;
    width += a.amp * a.ggx * a.alpha2;
  }
  const double horizon = t.horizon.cost(m.rho, m.f0);
  // The highlight about the geometric normal. Every mirror pair of the metric has h = z, and a
  // polished surface seen from afar shows its highlight there, so a merge that lowers or raises the
  // mixture's peak at h = z is charged for it (the blurred L2 above cannot see the height of narrow
  // peaks).
  peak -= Am * m.d_z;
  // The change of the amplitude-weighted core width Σ amp·μ·α² (α² = 1/P, lobe.h). For plain GGX
  // lobes μ·α² is the tail coefficient: far from the peak D ≈ μα²/(π·t²) (t = tan²θ), so a change Δ
  // of it changes D by Δ/(π·t²), whose squared L2 over slope space (dA = π·dt) from the resolution
  // outward, ∫ Δ²/(π·t⁴) dt over t > α²_res, is Δ²/(3π·α⁶_res). It keeps rough lobes of different
  // widths — the fingerprints' glow — from being merged into narrow ones, which the peak-dominated
  // terms above allow.
  width -= m.amp * m.ggx * m.alpha2;
  // The log profile: what the moments do not pin, the shape between peak and tail (profile_of), with
  // the lobes weighted by their amplitudes (by weight when no lobe has a specular part: !by_amp).
  const double k = by_amp ? Am : W;
  double e = 0;
  for (std::size_t j = 0; j < kProfileSteps; ++j) {
    double ex = 0;
    for (const Member& x : u) ex += (by_amp ? x.sum->amp : x.sum->weight) * x.sum->profile[j];
    const double ap = k * m.profile[j];
    if (ex > 0 && ap > 0) e += log_ratio2(ap, ex);
  }
  return std::max(0.0, spec) + horizon + peak_weight * peak * peak + width * width / kWidthNorm +
         kProfileWeight * k * k * e / kProfileSteps + trans_cost(u, t, m, peak_weight);
}

UnionTerms union_terms(std::span<const Member> u) {
  return {union_spec_norm2(u), horizon_sums(u, union_weight(u)), union_trans_norm2(u)};
}

namespace {
// rough_distance's transmission term. Two lobes of transmitted amplitudes a and b (per channel, sum
// S = a + b) and shapes T_a, T_b merge into one shape T_m near f·T_a + (1 − f)·T_b, f = Σa/ΣS the
// share of the amplitude (the merge keeps the amplitude-weighted tail and peak: lobe.h). Channel c
// keeps a_c·T_a + b_c·T_b − S_c·T_m = S_c·(f_c − f)·(T_a − T_b) of its colour's own mixture (f_c =
// a_c/S_c), and one shape for the mixture loses Ward's S_c²·f·(1 − f)·|T_a − T_b|² more; |T_a − T_b|²
// is rough_distance's shape term in the log-roughness, ln(α²_T,a/α²_T,b)²/4 over 2·(α²_T,a + α²_T,b +
// 2α²_res). So lobes transmitting the same colour through different widths, or different colours
// through different widths, are kept apart; equal widths merge exactly (τ is linear).
double trans_distance(const Summary& a, const Summary& b) {
  if (!has_transmission(a) && !has_transmission(b)) return 0.0;
  const glm::dvec3 S = a.trans + b.trans;
  const double total = S.x + S.y + S.z;
  if (!(total > 0)) return 0.0;
  const double f = (a.trans.x + a.trans.y + a.trans.z) / total;
  double colour = 0;
  for (int c = 0; c < 3; ++c) {
    const double fc = S[c] > 0 ? a.trans[c] / S[c] : f;
    colour += S[c] * S[c] * (f * (1 - f) + (fc - f) * (fc - f));
  }
  const double dl = series_log(std::max(a.alpha2_t, 1e-12) / std::max(b.alpha2_t, 1e-12));
  return colour / 3 * (0.25 * dl * dl) / (2.0 * (a.alpha2_t + b.alpha2_t + 2.0 * kResolutionAlpha2));
}
}  // namespace

double rough_distance(const Summary& a, const Summary& b) {
  const double w = a.weight + b.weight;
  const double ab = a.weight * b.weight / w;
  const double width = a.alpha2 + b.alpha2 + 2.0 * kResolutionAlpha2;
  const double amp = (a.amp + b.amp) / w;
  const glm::dvec3 dn = a.n - b.n;
  const double dn2 = glm::dot(dn, dn);
  const double dl = series_log(a.alpha2 / b.alpha2);
  const double rho = 0.5 * (a.rho + b.rho), f0 = 0.5 * (a.f0 + b.f0);
  const double horizon_amp = rho + f0 + 0.2 * (1.0 - f0);
  const double drho = a.rho - b.rho;
  // Stretched lobes also differ in ln α² along each axis by uᵀ·Δ(ln S)·u, whose mean square over the
  // axes u is |Δ stretch_log|²/2 (slope_stretch.h), weighted as the log-roughness.
  const glm::dvec2 dv = a.stretch_log - b.stretch_log;
  const double shape = 0.25 * dl * dl + 0.125 * glm::dot(dv, dv);
  return ab * (amp * amp / (2.0 * width) * (shape + dn2 / width) + 0.4 * horizon_amp * horizon_amp * std::sqrt(dn2)) +
         (4.0 / 3.0) * ab * ab * drho * drho * dn2 + trans_distance(a, b);
}

}  // namespace svbrdf::reduction
