#include "mip/lobe_reduction.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <tuple>
#include <utility>
#include <vector>

#include "appearance/microfacet_core.h"
#include "base/math.h"
#include "base/series_log.h"

namespace svbrdf {

namespace {

// The resolution below which the cost model stops telling specular lobes apart: every lobe is seen
// blurred by a GGX-like kernel of α² = kResolutionAlpha2 (α = 0.1, about 6°, the scale of the metric's
// direction grid). Without it the L2 norm of a lobe grows as 1/α², so the shape differences of
// mirror-like lobes (α ≈ 0.005 against 0.01) would outweigh everything else and a polished tray's
// soft fingerprint glow would be merged away to keep them apart.
constexpr double kResolutionAlpha2 = 0.01;
// The weight of the highlight-peak term of union_cost (see there). The blurred L2 of the cost cannot
// see a narrow lobe moved by a degree or two, but the mirror pairs can: at 1e-5 granite's mica flecks
// (α ≈ 0.02) were merged into tilted lobes at levels 2–3, the level means falling 4–7 % at the grazing
// mirror pairs (pink granite's e_mean 0.059; 0.019 at 2e-4). Too large and it keeps polished sub-lobes
// apart while the fingerprints' rough lobes are merged into them: their off-specular flux goes (e_log
// of metal-tray 0.037 at level 8 with 1e-3; −30 % to −50 % of that flux at 1). Even 2e-4 costs the
// tray's glow at small angles: its level-8 mean at θi = 20°, θo = 0° is +12 % (+3 % at 1e-5), at 45°
// and 75° within 1 % as before. bench/results/mip.md ("2026-11-23, second session") has the sweep.
constexpr double kPeakWeight = 2e-4;
// The weight for the first try of a texel's whole union as one lobe (reduce_lobes): that try asks
// whether the texel is smooth within the L2 budget, a norm with no peak term; it keeps the small weight.
constexpr double kWholePeakWeight = 1e-5;
// The share of the LEAN estimate in the peak of a merged lobe that becomes a spread core (merge_union).
constexpr double kLeanPeakShareSpread = 0.4;
// The weight of the log-profile term of merge_pair (the shape between peak and tail), and its steps.
constexpr double kProfileWeight = 25.0;
constexpr std::size_t kProfileSteps = 15;

double mean3(const glm::vec3& c) { return (double(c.x) + c.y + c.z) / 3.0; }

// A lobe's specular amplitude, its share of the reflected flux for the cost model: F0 plus a little
// for Fresnel's rise toward grazing angles, times its weight and cosine factor (the mean normal's
// length).
double specular_amp(double weight, double len, double f0) { return weight * len * (f0 + 0.05 * (1.0 - f0)); }

// What D of a lobe shape depends on (lobe_d), without the horizons' fields.
struct DShape {
  double alpha2 = 1, alpha2_hi = 0, lmean = 0, ggx = 1, skirt = 1;
  bool two_point = false;
  static DShape of(const LobeShape<double>& sh) {
    return {sh.alpha2, sh.alpha2_hi, sh.lmean, sh.ggx, sh.skirt, sh.two_point};
  }
};

// What the cost model needs of a lobe, computed once per lobe.
struct Summary {
  glm::dvec3 n{0, 0, 1};  // unit normal
  double weight = 0;
  double amp = 0;     // specular amplitude: its share of the reflected flux
  double d_z = 0;     // D at h = z (the geometric normal)
  double rho = 0;     // mean diffuse albedo
  double f0 = 0;      // mean F0
  double alpha2 = 1;  // the core's width 1/P, for the Gaussian model of union_cost
  double ggx = 1;     // μ, the GGX share of a spread core (lobe.h)
  double tail = 0;    // A: the tail coefficient, D ≈ A/(π t²) far out
  double peak = 1;    // P: π·D at the lobe's own normal
  DShape d_shape;     // its D's shape, for D away from its normal (merge_union)
  double flux = -1;   // its specular flux as keep_specular_flux measures it (< 0: not yet known)
  std::array<double, kProfileSteps> profile{};  // D about its own normal at tan²θ = 10^-6 … 10 (profile_of)
};

// D of a lobe shape at tan²θ = t from its normal: lobe_d's shapes written in t (cos²θ = 1/(1 + t)), so
// no vectors: GGX α²/(π·cos⁴θ·(α² + t)²), the mixture's μ·L(l, h)/(π·cos⁴θ·(l + t)(h + t)), Beckmann
// e^(−t/α²)/(π·α²·cos⁴θ), the exponential by series_exp (4e-7: the reduction compares shapes with
// these, for every candidate merge). 0 past 90° (t infinite).
double d_at_tan2(const DShape& sh, double t) {
  if (!std::isfinite(t)) return 0.0;
  const double a2 = sh.alpha2, q = (1 + t) * (1 + t) / kPiD;
  if (sh.alpha2_hi > 0) {
    const double hi = sh.alpha2_hi;
    const double upper = sh.two_point ? hi / ((t + hi) * (t + hi)) : sh.lmean / ((t + a2) * (t + hi));
    return q * (sh.ggx * upper + (1.0 - sh.ggx) * a2 / ((t + a2) * (t + a2)));
  }
  double d = sh.ggx * a2 / ((t + a2) * (t + a2));
  if (sh.ggx != 1.0) {
    const double b2 = a2 * sh.skirt, x = t / b2;
    if (x < 60.0) d += (1.0 - sh.ggx) * double(series_exp(static_cast<float>(-x))) / b2;
  }
  return q * d;
}

// D of a lobe shape about its own normal at kProfileSteps values of tan²θ, log-spaced from 1e-6 to 10:
// d_at_tan2 at each, its branches taken once for the row (this runs for every lobe summarized, and the
// loops over the steps then vectorize); the same arithmetic, so the same numbers. A loop of inlined
// d_at_tan2 calls made reduce_lobes 9 % slower per level-1 texel, hence the copy: change both together.
void profile_of(const DShape& sh, std::array<double, kProfileSteps>& out) {
  struct Steps {
    std::array<double, kProfileSteps> t{}, q{};  // tan²θ and d_at_tan2's (1 + t)²/π
  };
  static const Steps steps = [] {
    Steps s;
    for (std::size_t j = 0; j < kProfileSteps; ++j) {
      s.t[j] = std::pow(10.0, -6.0 + 7.0 * double(j) / (kProfileSteps - 1));
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

// tan²θ between two unit vectors (∞ at or past 90°).
double tan2_between(const glm::dvec3& a, const glm::dvec3& b) {
  const double c = glm::dot(a, b);
  if (c <= 1e-6) return INFINITY;
  return std::max(0.0, 1.0 / (c * c) - 1.0);
}

// D at h = z (the geometric normal) of a lobe.
double d_at_z(const LobeShape<double>& sh) {
  if (!sh.valid) return 0.0;
  return d_at_tan2(DShape::of(sh), tan2_between(sh.n, glm::dvec3(0, 0, 1)));
}

Summary summarize(const Lobe& l) {
  Summary s;
  const glm::dvec3 nbar(l.normal);
  const double len = glm::length(nbar);
  s.n = len > 0 ? nbar / len : glm::dvec3(0, 0, 1);
  s.weight = l.weight;
  s.rho = mean3(l.diffuse);
  s.f0 = mean3(l.f0);
  s.amp = specular_amp(l.weight, len, s.f0);
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
  return s;
}

// The L2 inner product, over (wi, wo) pairs, of two specular lobes of amplitude 1: each lobe's
// reflected radiance around its mirror direction approximated by a Gaussian of per-axis variance
// 2α² (the half vector's α²/2, doubled twice by the mirror map), their centres 2·tanθ apart.
// ∫ N(x; μa, Σa) N(x; μb, Σb) dx = N(μa − μb; 0, Σa + Σb) gives exp(−d²/(αa² + αb²)) / (4π(αa² + αb²)),
// times the 2π of wi; both lobes blurred to the resolution kResolutionAlpha2.
double spec_inner(double alpha2_a, double alpha2_b, double tan2) {
  if (!std::isfinite(tan2)) return 0.0;
  const double s = alpha2_a + alpha2_b + 2.0 * kResolutionAlpha2, x = tan2 / s;
  // Nearly parallel normals (most pairs of a smooth surface): e^−x by its series (within 3e-9).
  const double g = x < 0.05 ? 1 - x * (1 - x * (0.5 - x * (1.0 / 6 - x * (1.0 / 24)))) : std::exp(-x);
  return g / (2.0 * s);
}

// The specular albedo of a flat lobe, ∫ D·V·(F0 + (1 − F0)·w)·wo.z dωo = F0·a(α², θi) + (1 − F0)·b(α², θi),
// summed over θi ∈ {0°, 45°, 75°}, tabulated over log α² by quadrature (wo from GGX half vectors,
// stratified). GGX with the glTF visibility loses energy as α grows (single scattering), so merging a
// rough lobe into a sharp one would add flux; merges rescale the specular part to keep this albedo.
class SpecAlbedoTable {
 public:
  static const SpecAlbedoTable& get() {
    static const SpecAlbedoTable t;
    return t;
  }
  double albedo(double alpha2, double f0, double ggx) const {
    return albedo_at_log(series_log(std::clamp(alpha2, kMin, 1.0)), f0, ggx);
  }
  // The same at ln α² (clamped to the table).
  double albedo_at_log(double ln_alpha2, double f0, double ggx) const {
    const Cell c = cell(ln_alpha2);
    return ggx * (f0 * c.at(a_) + (1 - f0) * c.at(b_)) + (1 - ggx) * (f0 * c.at(ba_) + (1 - f0) * c.at(bb_));
  }
  // The same for μ = 1 (a GGX lobe; a roughness mixture's components), without the Beckmann columns.
  double ggx_albedo_at_log(double ln_alpha2, double f0) const {
    const Cell c = cell(ln_alpha2);
    return f0 * c.at(a_) + (1 - f0) * c.at(b_);
  }

 private:
  static constexpr int kSize = 128;
  static constexpr double kMin = 1e-6;
  // Where ln α² falls in the table: entry i and the share t of entry i + 1.
  struct Cell {
    int i;
    double t;
    double at(const std::array<double, kSize>& v) const {
      return v[static_cast<std::size_t>(i)] * (1 - t) + v[static_cast<std::size_t>(i + 1)] * t;
    }
  };
  static Cell cell(double ln_alpha2) {
    const double lmin = std::log(kMin);
    const double x = (std::clamp(ln_alpha2, lmin, 0.0) - lmin) / (-lmin) * (kSize - 1);
    const int i = std::min(kSize - 2, static_cast<int>(x));
    return {i, x - i};
  }
  SpecAlbedoTable() {
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
  std::array<double, kSize> a_{}, b_{}, ba_{}, bb_{};  // GGX and Beckmann columns
};

// The lobes of a union being merged: each lobe with its summary.
struct Member {
  const Lobe* lobe;
  const Summary* sum;
};

// Σ_ij amp_i·amp_j·⟨G_i, G_j⟩: the squared L2 norm of the union's specular lobes (spec_inner).
double union_spec_norm2(std::span<const Member> u) {
  double s = 0;
  for (std::size_t i = 0; i < u.size(); ++i) {
    const Summary& a = *u[i].sum;
    s += a.amp * a.amp * spec_inner(a.alpha2, a.alpha2, 0);
    for (std::size_t j = i + 1; j < u.size(); ++j) {
      const Summary& b = *u[j].sum;
      s += 2 * a.amp * b.amp * spec_inner(a.alpha2, b.alpha2, tan2_between(a.n, b.n));
    }
  }
  return s;
}

// Horizons: the linear part of the cosine factors is kept exactly, but where the lobes' horizons
// differ (a lune of width δ, the angle between the normals) the merged lobe's smooth horizon differs
// from theirs; diffuse and grazing specular (Fresnel rises toward 1) both feel it. Plus the coupling
// of color and normal (ρ̄·n̄ ≠ E[ρ·n]). The pairs' sums do not depend on the merged lobe, so a union's
// are made once for its bound and its cost: horizon = 0.4·H²·lune + coupling, where H is the merged
// lobe's amplitude at the horizon (its ρ and F0).
struct HorizonSums {
  double lune = 0;      // Σ w_a·w_b/W · δ_ab
  double coupling = 0;  // Σ (4/3)·(w_a·w_b/W)²·Δρ²·2(1 − cos δ_ab)
  double cost(double rho, double f0) const {
    const double amp = rho + f0 + 0.2 * (1.0 - f0);
    return 0.4 * amp * amp * lune + coupling;
  }
};

// W: the union's weight.
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

// A lower bound of union_cost that needs no merge: its horizon term alone (every other term is ≥ 0),
// with the merged ρ and F0 taken as the weighted means merge_base makes (less a relative 1e-6 for the
// float rounding of the merged lobe's).
double union_cost_bound(std::span<const Member> u, const HorizonSums& h) {
  double W = 0, rho = 0, f0 = 0;
  for (const Member& x : u) W += x.sum->weight, rho += x.sum->weight * x.sum->rho, f0 += x.sum->weight * x.sum->f0;
  return (1.0 - 1e-6) * h.cost(rho / W, f0 / W);
}

// The estimated squared error of replacing the union u by the lobe m, whose union has specular norm²
// `self` (union_spec_norm2): the specular L2 error of the Gaussian model, the horizons, the highlight
// about the geometric normal, the core widths and the log profile, each below. For two lobes these
// are the terms of the pair; for more, the pair terms summed over the pairs (horizons) or the union's
// sums in place of the pair's.
double union_cost(std::span<const Member> u, double self, const HorizonSums& hs, const Summary& m, bool by_amp,
                  double peak_weight) {
  double Am = 0, peak = 0, width = 0, spec = self, W = 0;
  for (const Member& x : u) Am += x.sum->amp, W += x.sum->weight;
  spec += Am * Am * spec_inner(m.alpha2, m.alpha2, 0);
  for (const Member& x : u) {
    const Summary& a = *x.sum;
    spec -= 2 * Am * a.amp * spec_inner(m.alpha2, a.alpha2, tan2_between(a.n, m.n));
    peak += a.amp * a.d_z;
    width += a.amp * a.ggx * a.alpha2;
  }
  const double horizon = hs.cost(m.rho, m.f0);
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
    if (ex > 0 && ap > 0) {
      // ln(ap/ex) = 2·atanh(q), q = (ap − ex)/(ap + ex): for the near matches that decide merges
      // (|q| < ½, a ratio within 3) the series to q⁹ (within 4e-5) in one division.
      const double q = (ap - ex) / (ap + ex), q2 = q * q;
      const double r = q2 < 0.25 ? 2 * q * (1 + q2 * (1.0 / 3 + q2 * (1.0 / 5 + q2 * (1.0 / 7 + q2 * (1.0 / 9)))))
                                 : series_log(ap / ex);
      e += r * r;
    }
  }
  return std::max(0.0, spec) + horizon + peak_weight * peak * peak +
         width * width / (3 * kPiD * kResolutionAlpha2 * kResolutionAlpha2 * kResolutionAlpha2) +
         kProfileWeight * k * k * e / kProfileSteps;
}

// The merged lobe but for its shape: the linear parts (weight, ρ, F0, mean normal).
struct MergeBase {
  Lobe lobe;
  Summary summary;  // all but the shape's
};

MergeBase merge_base(std::span<const Member> u) {
  MergeBase mb;
  Lobe& m = mb.lobe;
  double w = 0;
  for (const Member& x : u) w += x.lobe->weight;
  // Shares by one reciprocal: this runs for every candidate merge of every texel.
  const double inv_w = 1.0 / w;
  glm::dvec3 diffuse(0), f0(0), nbar(0);
  Summary& s = mb.summary;
  s.rho = s.f0 = 0;
  for (const Member& x : u) {
    const double t = x.lobe->weight * inv_w;
    diffuse += t * glm::dvec3(x.lobe->diffuse);
    f0 += t * glm::dvec3(x.lobe->f0);
    nbar += t * glm::dvec3(x.lobe->normal);
    s.rho += t * x.sum->rho;
    s.f0 += t * x.sum->f0;
  }
  m.weight = static_cast<float>(w);
  m.diffuse = glm::vec3(diffuse);
  m.f0 = glm::vec3(f0);
  m.normal = glm::vec3(nbar);
  const double len = glm::length(nbar);
  s.n = len > 0 ? nbar * (1.0 / len) : glm::dvec3(0, 0, 1);
  s.weight = w;
  s.amp = specular_amp(w, len, s.f0);
  return mb;
}

// The merged lobe of a union, with its summary and estimated cost.
struct Merged {
  Lobe lobe;
  Summary summary;
  double cost = 0;
};

// The inverse of sinh(u)/u = T (T ≥ 1) to ~1e-5, for band_span's Newton iteration to start from
// (one step then reaches 1e-10): tabulated over w = ln(1 + √(T − 1)), in which u is smooth (u ≈ √(6(T − 1))
// near T = 1, ≈ ln(2T·ln 2T) far out), by bisection once.
class SinhcInverse {
 public:
  static const SinhcInverse& get() {
    static const SinhcInverse t;
    return t;
  }
  double guess(double target) const {
    const double w = series_log(1.0 + std::sqrt(std::max(0.0, target - 1.0)));
    if (!(w < kMaxW)) return std::log(2.0 * target * std::log(2.0 * target + 1.0) + 1.0);
    const double x = w / kMaxW * (kSize - 1);
    const int i = std::min(kSize - 2, static_cast<int>(x));
    const double t = x - i;
    return u_[static_cast<std::size_t>(i)] * (1 - t) + u_[static_cast<std::size_t>(i + 1)] * t;
  }

 private:
  static constexpr int kSize = 1024;
  static constexpr double kMaxW = 4.0;  // T up to 1 + (e⁴ − 1)² ≈ 2900
  SinhcInverse() {
    for (int k = 0; k < kSize; ++k) {
      const double v = std::expm1(kMaxW * k / (kSize - 1)), target = 1.0 + v * v;
      double lo = 0, hi = 20;
      for (int it = 0; it < 80; ++it) {
        const double mid = 0.5 * (lo + hi);
        (mid > 0 && std::sinh(mid) / mid < target ? lo : hi) = mid;
      }
      u_[static_cast<std::size_t>(k)] = 0.5 * (lo + hi);
    }
  }
  std::array<double, kSize> u_{};
};

// The cone a spread core's skirt is fitted in: the mass of D within 2.82° of the merged normal, the
// disc of the area of the ±2.5° square of half vectors that a 10° field of view spans (the LOD scenes'
// camera, whose images integrate D over that square). The resolution at which the skirt keeps the
// union's shape, as kResolutionAlpha2 is the cost's: at 2.5° (the square's inscribed disc) polished
// granite's highlight kept +2.5 % at level 8, at 2.82° +1.3–1.4 % (bench/results/mip.md).
constexpr double kSkirtTan2 = 0.0024279912;  // tan²(2.8209°), 2.8209° = √(25/π)°
// Cores get a skirt while P·kSkirtTan2 exceeds this (α² below 2.5·kSkirtTan2: a core within ~4.5°).
constexpr double kSkirtMinPeak = 0.4;

// 1 − e^(−x) for x ≥ 0 within 4e-7 (series_exp; the series near 0, where the difference would cancel):
// the cone masses below run for every candidate merge that makes a narrow spread core.
double one_minus_exp(double x) {
  return x < 1e-2 ? x * (1.0 - x * (0.5 - x / 6.0)) : 1.0 - double(series_exp(static_cast<float>(-x)));
}

// The mass within slope radius R of an axis of a GGX slope distribution α²/(π(α² + |s|²)²) (slope
// space: tan θ, small angles) whose normal lies at slope distance d from the axis. In closed form:
// the angle about the axis integrates to 2π·a/(a² − b²)^{3/2} (a = α² + ρ² + d², b = 2ρd), and in
// x = ρ² the rest is ∫ α²(y + 2d²)/(y² + 4α²d²)^{3/2} dy with y = x + α² − d², whose antiderivative is
// (y/2 − α²)/√(y² + 4α²d²). At d = 0 this is R²/(α² + R²), GGX's radial CDF.
double ggx_disc_mass(double a2, double d2, double R2) {
  const double k2 = 4.0 * a2 * d2;
  const auto at = [&](double y) { return (0.5 * y - a2) / std::sqrt(y * y + k2); };
  return at(R2 + a2 - d2) - at(a2 - d2);
}

// e^(−x)·I0(x) for x ≥ 0 (I0 the modified Bessel function of order 0), within 2e-7 relative:
// Abramowitz & Stegun 9.8.1 (x ≤ 3.75) and 9.8.2 (above).
double scaled_bessel_i0(double x) {
  if (x <= 3.75) {
    const double t2 = (x / 3.75) * (x / 3.75);
    return double(series_exp(static_cast<float>(-x))) *
           (1.0 + t2 * (3.5156229 + t2 * (3.0899424 + t2 * (1.2067492 + t2 * (0.2659732 + t2 * (0.0360768 + t2 * 0.0045813))))));
  }
  const double s = 3.75 / x;
  return (0.39894228 + s * (0.01328592 + s * (0.00225319 + s * (-0.00157565 + s * (0.00916281 + s * (-0.02057706 +
          s * (0.02635537 + s * (-0.01647633 + s * 0.00392377)))))))) / std::sqrt(x);
}

// Gauss–Legendre nodes and weights on [0, 1], by Newton's method on the Legendre polynomial.
template <int N>
struct GaussLegendre {
  std::array<double, N> x{}, w{};
  GaussLegendre() {
    for (int i = 0; i < N; ++i) {
      double z = std::cos(kPiD * (i + 0.75) / (N + 0.5)), dp = 1.0;
      for (int it = 0; it < 100; ++it) {
        double p0 = 1.0, p1 = z;  // P_0, P_1, then up to P_N by the three-term recurrence
        for (int k = 2; k <= N; ++k) {
          const double p2 = ((2 * k - 1) * z * p1 - (k - 1) * p0) / k;
          p0 = p1, p1 = p2;
        }
        dp = N * (z * p1 - p0) / (z * z - 1.0);
        const double step = p1 / dp;
        z -= step;
        if (std::abs(step) < 1e-15) break;
      }
      x[static_cast<std::size_t>(i)] = 0.5 * (1.0 - z);
      w[static_cast<std::size_t>(i)] = 1.0 / ((1.0 - z * z) * dp * dp);  // 2/((1 − z²)P'²), halved for [0, 1]
    }
  }
};

// The mass within slope radius R of an axis of a Beckmann (Gaussian) slope distribution e^(−|s|²/b²)/(πb²)
// whose normal lies at slope distance d from the axis (as ggx_disc_mass): about the axis, the angle
// integrates to 2π·e^(−(ρ² + d²)/b²)·I0(2ρd/b²), and the radius ρ ∈ [0, R] — where that is a smooth
// bump of width b about d — by 4-point Gauss–Legendre on panels of at most 1.5b over the part within
// 4.5b of d (e^(−20) beyond): within 1.1e-5 of a 4000 × 2000 grid for b² from 3e-5 to 2e-2.
double beckmann_disc_mass(double b2, double d, double R) {
  const double b = std::sqrt(b2);
  if (R - d >= 4.5 * b) return 1.0;
  if (d - R >= 4.5 * b) return 0.0;
  if (d >= 8.0 * b) {
    // A bump narrow against its distance d from the axis: with e^(−x)·I0(x) ≈ (1 + 1/(8x))/√(2πx) and
    // √(ρ/d) to second order in ρ − d, the integral is Gaussian moments up to z = (R − d)/b:
    // ½erfc(−z) − (b/(4√π·d) − b²z/(16√π·d²))·e^(−z²), within 3e-6 for b ≤ d/8.
    const double z = (R - d) / b, g = std::exp(-z * z) * 0.56418958354775628 / d;  // 1/√π
    return 0.5 * std::erfc(-z) - g * b * (0.25 - b * z / (16.0 * d));
  }
  const double lo = std::max(0.0, d - 4.5 * b), hi = std::min(R, d + 4.5 * b);
  static const GaussLegendre<4> gl;
  const int panels = std::max(1, static_cast<int>(std::ceil((hi - lo) / (1.5 * b))));
  const double width = (hi - lo) / panels;
  double m = 0.0;
  for (int p = 0; p < panels; ++p)
    for (std::size_t j = 0; j < gl.x.size(); ++j) {
      const double rho = lo + width * (p + gl.x[j]), e = (rho - d) * (rho - d) / b2;
      m += gl.w[j] * rho * double(series_exp(static_cast<float>(-e))) * scaled_bessel_i0(2.0 * rho * d / b2);
    }
  return m * width * 2.0 / b2;
}

// The mass of a lobe shape whose normal lies at slope distance d from an axis within slope radius R of
// that axis (slopes add: LEAN): its GGX share in closed form (a roughness mixture's by 4-point
// Gauss–Legendre in ln α², where that mass is smooth), its Beckmann share at c·α² by quadrature.
double cone_mass_at(const DShape& sh, double d, double R) {
  const double R2 = R * R, d2 = d * d, a2 = sh.alpha2;
  if (sh.alpha2_hi > 0) {
    double upper;
    if (sh.two_point) {
      upper = ggx_disc_mass(sh.alpha2_hi, d2, R2);
    } else {
      static const GaussLegendre<4> gl;
      const double span = (sh.alpha2_hi - a2) / sh.lmean;  // ln(h/l) = (h − l)/L(l, h) (lobe.h)
      upper = 0.0;
      for (std::size_t k = 0; k < gl.x.size(); ++k) upper += gl.w[k] * ggx_disc_mass(a2 * std::exp(gl.x[k] * span), d2, R2);
    }
    return sh.ggx * upper + (sh.ggx != 1.0 ? (1.0 - sh.ggx) * ggx_disc_mass(a2, d2, R2) : 0.0);
  }
  double m = sh.ggx * ggx_disc_mass(a2, d2, R2);
  if (sh.ggx != 1.0) m += (1.0 - sh.ggx) * beckmann_disc_mass(a2 * sh.skirt, d, R);
  return m;
}

// cone_mass_at for a lobe whose normal is the axis (d = 0), in closed form: GGX's radial CDF
// R²/(α² + R²), its log-uniform mean over a band, Beckmann's 1 − e^(−R²/b²). A lobe tilted off the axis
// has less there (a radially decreasing density has most mass in a disc centred on its mode), so
// this bounds a union's mass in the disc from above, at no quadrature.
double centred_cone_mass(const DShape& sh, double R2) {
  const double a2 = sh.alpha2;
  if (sh.alpha2_hi > 0) {
    const double hi = sh.alpha2_hi;
    const double upper = sh.two_point ? R2 / (hi + R2) : 1.0 + series_log((a2 + R2) / (hi + R2)) / series_log(hi / a2);
    return sh.ggx * upper + (1.0 - sh.ggx) * R2 / (a2 + R2);
  }
  double m = sh.ggx * R2 / (a2 + R2);
  if (sh.ggx != 1.0) m += (1.0 - sh.ggx) * one_minus_exp(R2 / (a2 * sh.skirt));
  return m;
}

// Roughness mixtures with an atom (lobe.h), in units of 1/P: the atom at x = lP ≤ 1, the upper end
// y = hP, the upper part's share β. Each has tail q = AP and peak 1; the third number, the mass within
// slope radius 1/√P (the core), picks one of a one-parameter family (fit_atom_band, fit_two_point).
struct MixtureFit {
  double x = 1, y = 1, beta = 1;
  bool two_point = false;
  // The mass within slope radius² s/P (closed forms: GGX's radial CDF s/(s + a), and its log-uniform
  // mean 1 + ln((s + x)/(s + y))/ln(y/x) over the band); t = ln(y/x) when known.
  double mass(double s, double t = 0) const {
    const double upper = two_point ? s / (s + y) : 1.0 + series_log((s + x) / (s + y)) / (t > 0 ? t : series_log(y / x));
    return (1 - beta) * s / (s + x) + beta * upper;
  }
};

// Finds where f (continuous) crosses 0 on [lo, hi], given f_lo = f(lo) and f_hi = f(hi) (of opposite
// signs; else the end nearer 0): `bisections` halvings first (where f is flat at the ends, as a sigmoid
// is), then regula falsi with the Illinois rule (halve the value kept at an end that stays twice), to
// |f| < tol or max_steps steps in all.
template <class F>
double illinois_root(F&& f, double lo, double f_lo, double hi, double f_hi, double tol, int bisections = 0,
                     int max_steps = 40) {
  if (!(f_lo * f_hi < 0)) return std::abs(f_lo) <= std::abs(f_hi) ? lo : hi;
  double t = lo;
  int kept = 0;  // +1: lo moved last, −1: hi moved last
  for (int it = 0; it < max_steps; ++it) {
    const bool falsi = it >= bisections;
    t = falsi ? (lo * f_hi - hi * f_lo) / (f_hi - f_lo) : 0.5 * (lo + hi);
    const double v = f(t);
    if (std::abs(v) < tol) break;
    if ((v < 0) == (f_lo < 0)) {
      lo = t, f_lo = v;
      if (falsi && kept == 1) f_hi *= 0.5;
      kept = 1;
    } else {
      hi = t, f_hi = v;
      if (falsi && kept == -1) f_lo *= 0.5;
      kept = -1;
    }
  }
  return t;
}

// The atom-and-band family's quadratic in β at t = ln(y/x) (fit_atom_band): a·b·β² − (b − a)·β + (q − 1)
// with a = 1 − g, b = k − 1, g = (1 − e^−t)/t, k = (e^t − 1)/t; its discriminant, and e^t.
struct AtomBandTerms {
  double a, b, disc, e;
  static AtomBandTerms at(double q, double t) {
    const double e = std::exp(t), g = (1 - 1 / e) / t, k = (e - 1) / t, a = 1 - g, b = k - 1;
    return {a, b, (b - a) * (b - a) - 4 * a * b * (q - 1), e};
  }
};

// Where the atom-and-band family's two roots meet (fit_atom_band), as a function of q alone: tabulated
// over ln q ∈ [0, 40] by bisection once, and read slightly above (1e-4), where the roots are real.
class FoldTable {
 public:
  static const FoldTable& get() {
    static const FoldTable t;
    return t;
  }
  double t_min(double q) const {
    const double x = std::clamp(series_log(q) / kMaxLnQ, 0.0, 1.0) * (kSize - 1);
    const int i = std::min(kSize - 2, static_cast<int>(x));
    const double f = x - i;
    return (t_[static_cast<std::size_t>(i)] * (1 - f) + t_[static_cast<std::size_t>(i + 1)] * f) * (1 + 1e-4);
  }

 private:
  static constexpr int kSize = 512;
  static constexpr double kMaxLnQ = 40.0;
  FoldTable() {
    for (int k = 0; k < kSize; ++k) {
      const double q = std::exp(kMaxLnQ * k / (kSize - 1)) * (1 + 1e-9);
      double lo = 1e-6, hi = 60;
      for (int it = 0; it < 60; ++it) (AtomBandTerms::at(q, 0.5 * (lo + hi)).disc < 0 ? lo : hi) = 0.5 * (lo + hi);
      t_[static_cast<std::size_t>(k)] = hi;
    }
  }
  std::array<double, kSize> t_{};
};

// The atom and a log-uniform band [x, y] over it, with core mass `core`. In t = ln(y/x), with
// g = (1 − e^−t)/t and k = (e^t − 1)/t, the peak gives x = 1 − β(1 − g) and the tail x(1 + β(k − 1)) = q, so
// β solves AtomBandTerms' quadratic. Its roots meet at t_min; from the band alone
// (β = 1 at t = t_band, the log-uniform mixture) the upper root runs down to t_min and the lower one on to
// β → 0 as t → ∞, and along that path the core mass rises from the band's to ½: the root on the branch
// that holds `core`, with y ≤ y_max (α² ≤ 1).
MixtureFit fit_atom_band(double q, double t_band, double core, double y_max) {
  const auto at = [&](double t, bool upper_root) {
    const AtomBandTerms c = AtomBandTerms::at(q, t);
    MixtureFit f;
    f.beta = std::clamp(((c.b - c.a) + (upper_root ? 1 : -1) * std::sqrt(std::max(0.0, c.disc))) / (2 * c.a * c.b), 0.0, 1.0);
    f.x = 1 - f.beta * c.a;
    f.y = f.x * c.e;
    return f;
  };
  const double t_min = std::min(FoldTable::get().t_min(q), t_band);
  const bool upper_root = core <= at(t_min, true).mass(1, t_min);
  const double t_end = upper_root ? t_band : std::max(t_min, std::min(40.0, std::log(y_max)));
  const auto excess = [&](double t) { return at(t, upper_root).mass(1, t) - core; };
  return at(illinois_root(excess, t_min, excess(t_min), t_end, excess(t_end), 1e-5), upper_root);
}

// Two atoms at x and y with core mass `core`: the moments give β = y(1 − x)/(y − x) and
// y²(1 − x) + y(x² − q) + (qx − x²) = 0 (its root ≥ 1); the core mass rises with x from 1/(1 + q) (x → 0)
// to ½ (x → 1): the root in x, with y ≤ y_max (α² ≤ 1; y grows with x).
MixtureFit fit_two_point(double q, double core, double y_max) {
  const auto at = [&](double x) {
    MixtureFit f;
    f.two_point = true;
    f.x = x;
    const double b = x * x - q, c = q * x - x * x, a = 1 - x;
    f.y = (-b + std::sqrt(std::max(0.0, b * b - 4 * a * c))) / (2 * a);
    f.beta = f.y * (1 - x) / (f.y - x);
    return f;
  };
  // y = y_max where x²(Y − 1) + x(q − Y²) + Y(Y − q) = 0 (the quadratic at y = Y): its root in (0, 1).
  constexpr double kLo = 1e-9, kHi = 1 - 1e-9;
  const double Y = y_max, qa = Y - 1, qb = q - Y * Y, qc = Y * (Y - q);
  const double x_max = qa > 0 ? (-qb - std::sqrt(std::max(0.0, qb * qb - 4 * qa * qc))) / (2 * qa) : kHi;
  const double hi = std::clamp(x_max, kLo, kHi);
  const auto excess = [&](double x) { return at(x).mass(1) - core; };
  return at(illinois_root(excess, kLo, excess(kLo), hi, excess(hi), 1e-5));
}

// Where a log-uniform band's core mass falls this far below the union's, the union is sharper at its
// centre than a band can be (sharp lobes with rough ones: the fingerprinted tray, 30–40 % short) and
// gets an atom. At 2 % atoms also reach polished granite's unions of spread cores with mica flecks and
// raise its highlight over ±1° of views by 1–3 %; at 20 % the tray keeps half its loss (bench/results/mip.md,
// "eighth session").
constexpr double kAtomCoreShortfall = 0.1;

// The half span u of the log-uniform band with tail q = AP in units of its peak: sinh(u)/u = √q (the
// band is [g/e^u, g·e^u], g = √(A/P)), by Newton's method from the tabulated guess; and e^u.
struct BandSpan {
  double u, e;
};
BandSpan band_span(double q) {
  const double target = std::sqrt(q);
  double u = std::max(1e-6, SinhcInverse::get().guess(target));
  double e = std::exp(u);
  for (int k = 0; k < 8; ++k) {
    const double inv_e = 1 / e, sh = 0.5 * (e - inv_e), ch = 0.5 * (e + inv_e);
    // f = sinh(u)/u − T, f' = (u·cosh u − sinh u)/u², so the step f/f' = u·(sinh u − T·u)/(u·cosh u − sinh u).
    const double den = u * ch - sh;
    if (!(den > 0)) break;
    const double step = u * (sh - target * u) / den;
    const double next = std::max(1e-6, u - step), d = u - next;
    // e^next = e^u·e^−d; the steps from the tabulated guess are small (|d| ~ 1e-5·u, then ~1e-10),
    // where e^−d's series to d⁴ is exact to 1e-17: one exponential per shape, not one per step.
    e = std::abs(d) < 1e-3 ? e * (1 - d * (1 - d * (0.5 - d * (1.0 / 6 - d * (1.0 / 24))))) : std::exp(next);
    u = next;
    if (std::abs(step) < 1e-9 * u) break;
  }
  return {u, e};
}

// The lobe shape with tail coefficient A and peak P (lobe.h): when AP ≥ 1 a roughness mixture, the
// log-uniform band on [g/e^u, g·e^u] (band_span) unless the union is sharper at its centre than that
// band, else one core of α² = 1/P whose GGX share μ = AP thins the tail (the rest Beckmann).
// union_mass(R²), when given, is the union's mass within slope radius² R² of the merged normal (per unit
// of its amplitude, as A and P), and mass_bound(R²) a cheap upper bound of it.
//
// Why the atom: a band's mass within the core (slope radius 1/√P) is fixed by q alone, and a union of
// sharp lobes with rough ones — polished metal with fingerprints, clean at one texel and oily at the
// next — has far more there: a band with its A and P spreads the sharp lobes' peak over the decades
// between (−30 % of the tray's highlight over ±1° of views at some level-4 texels; −5.4 % over the whole
// tray by level 8). The atom's share is fitted to the union's core mass, and the upper part is a band
// or a second atom, whichever then keeps the union's mass in the LOD camera's cone (kSkirtTan2) better:
// a band for a sharp cluster over a spread of rough lobes, an atom for two clusters.
// bench/results/mip.md, "eighth session".
template <class UnionMass, class MassBound>
void set_shape(Lobe& m, double A, double P, const UnionMass* union_mass, const MassBound* mass_bound) {
  A = std::max(A, 1e-9);
  P = std::max(P, 1.0);
  const double q = A * P;
  m.alpha2_hi = 0.0f;
  m.skirt = 1.0f;
  if (q > 1.0 + 1e-7) {
    const BandSpan span = band_span(q);
    const double g = std::sqrt(A / P);
    m.alpha2 = static_cast<float>(std::clamp(g / span.e, 1e-6, 1.0));
    m.alpha2_hi = static_cast<float>(std::clamp(g * span.e, double(m.alpha2), 1.0));
    m.ggx = 1.0f;
    if (!union_mass) return;
    MixtureFit band;
    band.x = P * g / span.e, band.y = P * g * span.e;
    // Most unions are near the band's own shape: the bound rules them out without the quadratures.
    const double band_core = band.mass(1);
    if (!(band_core < (*mass_bound)(1 / P) * (1 - kAtomCoreShortfall))) return;
    const double core = (*union_mass)(1 / P);
    if (!(band_core < core * (1 - kAtomCoreShortfall))) return;
    const MixtureFit a = fit_atom_band(q, 2 * span.u, core, P), b = fit_two_point(q, core, P);
    const double cam = (*union_mass)(kSkirtTan2), s = kSkirtTan2 * P;
    // (Taking the band whenever it is within 1 % of the cone, to save the second fit, raised polished
    // granite's highlight at level 7 from +1.6 % to +3.3 %: the better of the two compounds.)
    const MixtureFit& f = std::abs(a.mass(s) - cam) <= std::abs(b.mass(s) - cam) ? a : b;
    // The upper end at least 0.2 % above the atom: what the MIP file stores as a mixture (0.1 %,
    // brdf_pyramid.h) once α is rounded to a half (5e-4 on α²).
    const double l = std::clamp(f.x / P, 1e-6, 1.0);
    if (l * 1.002 > 1.0) return;
    m.alpha2 = static_cast<float>(l);
    m.alpha2_hi = static_cast<float>(std::clamp(f.y / P, l * 1.002, 1.0));
    m.ggx = static_cast<float>(std::clamp(f.beta, 1e-3, 1.0));
    m.skirt = f.two_point ? 0.0f : 1.0f;
  } else {
    m.alpha2 = static_cast<float>(std::clamp(1.0 / P, 1e-6, 1.0));
    m.ggx = static_cast<float>(std::clamp(q, 0.0, 1.0));
    // The skirt: the Beckmann share widens to c·α² and, to keep the peak and the tail, the GGX share
    // rises to μ (α² = A/μ) with c = μ(1 − μ)/(AP − μ²), i.e. μ = 2c·AP/(1 + √(1 + 4c·AP·(c − 1)))
    // (μ = AP at c = 1, → √AP as c grows). That moves mass from inside the cone of kSkirtTan2 to just
    // outside it; c is solved for the union's mass in the cone, in ln c ∈ [0, ln 10⁴] where the mass is
    // smooth: 4 bisections (the mass is a sigmoid in ln c, flat until the skirt reaches the cone and
    // again once it is far outside), then regula falsi with the Illinois rule, to 1e-4 of mass (the
    // members' masses are good to 2e-4); c = 10⁴ where even that skirt keeps too much in the cone.
    const double R2 = kSkirtTan2;
    const double cone_mass = union_mass && P * R2 > kSkirtMinPeak ? (*union_mass)(R2) : -1.0;
    const auto share = [&](double c) { return 2.0 * c * q / (1.0 + std::sqrt(1.0 + 4.0 * c * q * (c - 1.0))); };
    const auto excess = [&](double t) {
      const double c = double(series_exp(static_cast<float>(t))), mu = share(c), a2 = A / mu;
      return mu * R2 / (a2 + R2) + (1.0 - mu) * one_minus_exp(R2 / (c * a2)) - cone_mass;
    };
    constexpr double kMaxLnSkirt = 9.210340371976184;  // ln 10⁴
    constexpr int kBisections = 4;
    double f_lo;
    if (cone_mass >= 0 && q > 1e-9 && q < 1 - 1e-6 && (f_lo = excess(0.0)) > 1e-4) {
      const double f_hi = excess(kMaxLnSkirt);
      const double t = f_hi < 0 ? illinois_root(excess, 0.0, f_lo, kMaxLnSkirt, f_hi, 1e-4, kBisections, 60) : kMaxLnSkirt;
      const double c = double(series_exp(static_cast<float>(t))), mu = share(c);
      if (c > 1.0001) {
        m.alpha2 = static_cast<float>(std::clamp(A / mu, 1e-6, 1.0));
        m.ggx = static_cast<float>(mu);
        m.skirt = static_cast<float>(c);
      }
    }
  }
}

// What union_cost needs of the union alone: its specular norm² (union_spec_norm2) and horizon sums.
struct UnionTerms {
  double self = 0;
  HorizonSums horizon;
};

UnionTerms union_terms(std::span<const Member> u) { return {union_spec_norm2(u), horizon_sums(u, union_weight(u))}; }

// Merges the union u; returns the merged lobe, its summary and, when the union's terms are given (a
// candidate merge, not one already chosen), its cost.
Merged merge_union(std::span<const Member> u, const UnionTerms* terms, float spread_scale, double peak_weight = kPeakWeight) {
  const MergeBase mb = merge_base(u);
  double K = 0;
  for (const Member& x : u) K += x.sum->amp;
  const bool by_amp = K > 0;
  if (!by_amp)
    for (const Member& x : u) K += x.sum->weight;
  const glm::dvec3& n = mb.summary.n;
  // The union's π·D at the merged normal, and its mass within slope radius² R² of it (each per unit of
  // K, as A and P below).
  const auto union_centre = [&] {
    double centre = 0;
    for (const Member& x : u) {
      const Summary& a = *x.sum;
      centre += (by_amp ? a.amp : a.weight) * kPiD * d_at_tan2(a.d_shape, tan2_between(a.n, n));
    }
    return centre / K;
  };
  const auto union_mass = [&](double R2) {
    const double R = std::sqrt(R2);
    double mass = 0;
    for (const Member& x : u) {
      const Summary& a = *x.sum;
      const double t = tan2_between(a.n, n);
      if (std::isfinite(t)) mass += (by_amp ? a.amp : a.weight) * cone_mass_at(a.d_shape, std::sqrt(t), R);
    }
    return mass / K;
  };
  // Moments of the union about the merged normal: the tails add (A), and each lobe's peak, widened
  // by its tilt to the merged normal (LEAN: α² + tan²θ, Olano & Baker 2010), adds (P_lean). When A and
  // that P make a spread core (A·P < 1: narrow lobes spread by their normals), P_lean overestimates
  // the union's centre (by about ln(2σ²/α²) for a Gaussian spread σ) and the error compounds over the
  // levels (+8 % at granite's mirror pairs by level 8); the union's exact D at the merged normal
  // (P_centre) alone underestimates it for the next level (−9 %: the union's core is flatter than a
  // spread core's). The spread core takes a blend, kLeanPeakShareSpread of P_lean; a roughness
  // mixture keeps P_lean for its band (a blend there moved metal-tray's off-specular level means by
  // 5–7 %), and so does its atom where it gets one (set_shape; P_centre there raised polished granite's
  // highlight by 2–3 % and lowered the tray's glow under a 45° sun by 1–2 %). bench/results/mip.md,
  // "2026-11-23, second session" and "eighth session".
  double A = 0, P_lean = 0;
  for (const Member& x : u) {
    const Summary& a = *x.sum;
    const double k = by_amp ? a.amp : a.weight;
    const double t = std::min(tan2_between(a.n, n), 1e3);
    A += k * a.tail;
    P_lean += k / (1.0 / a.peak + spread_scale * t);
  }
  double P = P_lean;
  if (A * P_lean < K * K) P = (1.0 - kLeanPeakShareSpread) * union_centre() * K + kLeanPeakShareSpread * P_lean;
  // A spread core narrower than a few degrees gets a skirt fitted to the union's mass in the cone of
  // kSkirtTan2 (set_shape): with its peak and tail kept, a one-width core puts into that cone the
  // mass the union spreads just outside it (texels tilted by 1–3°), +2 to +3.5 % on polished granite's
  // highlight from level 5 on. Wider cores (the tile roof's slopes, honed granite) keep c = 1: their
  // unions have no such shoulder, and slopes stop adding at their tilts. bench/results/mip.md,
  // "sixth session" and "seventh session". A roughness mixture whose union is sharper at its centre
  // than a log-uniform band gets an atom, fitted to the union's mass within the core (set_shape).
  const auto mass_bound = [&](double R2) {
    double mass = 0;
    for (const Member& x : u) mass += (by_amp ? x.sum->amp : x.sum->weight) * centred_cone_mass(x.sum->d_shape, R2);
    return mass / K;
  };
  Merged best{mb.lobe, mb.summary, 0};
  set_shape(best.lobe, A / K, P / K, &union_mass, &mass_bound);
  best.summary = summarize(best.lobe);
  if (terms) best.cost = union_cost(u, terms->self, terms->horizon, best.summary, by_amp, peak_weight);
  return best;
}

Merged merge_pair(const Lobe& a, const Summary& sa, const Lobe& b, const Summary& sb, float spread_scale,
                  bool with_cost = true) {
  const std::array<Member, 2> u{Member{&a, &sa}, Member{&b, &sb}};
  if (!with_cost) return merge_union(u, nullptr, spread_scale);
  const UnionTerms terms = union_terms(u);
  return merge_union(u, &terms, spread_scale);
}

// Keeps the union's specular albedo: scales the merged lobe's weight (which scales its specular part)
// and divides its ρ by the same factor (which leaves its diffuse part as it was). Applied when a merge
// is made, not while costs are estimated (it changes them by a few percent of the amplitude only).
void keep_specular_flux(std::span<const Member> u, Merged& m) {
  const SpecAlbedoTable& t = SpecAlbedoTable::get();
  auto albedo = [&](const Lobe& l) {
    double spec = 0;
    if (l.alpha2_hi > l.alpha2) {
      // A roughness mixture reflects the mean of its components' albedos: its band's over log-uniform α²
      // (midpoint rule in log α², 8 points), or its upper atom's, and its lower atom's.
      const double lo = series_log(double(l.alpha2)), f0 = mean3(l.f0);
      if (l.skirt == 0.0f) {
        spec = t.ggx_albedo_at_log(series_log(double(l.alpha2_hi)), f0);
      } else {
        const double step = series_log(double(l.alpha2_hi) / double(l.alpha2)) / 8;
        for (int k = 0; k < 8; ++k) spec += t.ggx_albedo_at_log(lo + (k + 0.5) * step, f0) / 8;
      }
      spec = l.ggx * spec + (1 - l.ggx) * t.ggx_albedo_at_log(lo, f0);
    } else {
      spec = l.skirt > 1.0f ? l.ggx * t.albedo(l.alpha2, mean3(l.f0), 1.0) +
                                  (1 - l.ggx) * t.albedo(double(l.alpha2) * l.skirt, mean3(l.f0), 0.0)
                            : t.albedo(l.alpha2, mean3(l.f0), l.ggx);
    }
    return double(l.weight) * glm::length(glm::dvec3(l.normal)) * spec;
  };
  // A lobe made by an earlier merge knows its flux (it was set to keep its lobes' there).
  double want = 0;
  for (const Member& x : u) want += x.sum->flux >= 0 ? x.sum->flux : albedo(*x.lobe);
  const double have = albedo(m.lobe);
  m.summary.flux = have;
  if (have > 0 && want > 0) {
    const double scale = want / have;
    m.lobe.weight = static_cast<float>(m.lobe.weight * scale);
    m.lobe.diffuse = glm::vec3(glm::dvec3(m.lobe.diffuse) / scale);
    // What of the summary the weight and ρ enter (its shape is unchanged).
    const double len = glm::length(glm::dvec3(m.lobe.normal));
    m.summary.weight = m.lobe.weight;
    m.summary.rho = mean3(m.lobe.diffuse);
    m.summary.f0 = mean3(m.lobe.f0);
    m.summary.amp = specular_amp(m.lobe.weight, len, m.summary.f0);
    m.summary.flux = want;
  }
}

// For unions of rough lobes only (α² at or above the resolution, where shapes are smooth and no peak
// needs keeping): a cheap stand-in for union_cost that orders the merges down to max_lobes the same
// way on the presets (bench/results/mip.md) at a tenth of the cost — Ward's criterion (the product of
// the weights over their sum) times the squared distance of the shapes (log-roughness, the normals'
// offset relative to the lobes' widths) scaled by the specular amplitude's L2 norm, plus the horizon
// term of union_cost.
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
  return ab * (amp * amp / (2.0 * width) * (0.25 * dl * dl + dn2 / width) + 0.4 * horizon_amp * horizon_amp * std::sqrt(dn2)) +
         (4.0 / 3.0) * ab * ab * drho * drho * dn2;
}

// The pair (i < j < n) with the least M(i, j), the first of equals. Without data-dependent branches:
// which of a texel's many near-equal costs is least is a coin toss a branch would mispredict.
template <class M>
std::pair<int, int> cheapest_pair(int n, M&& m) {
  double best = INFINITY;
  int bi = 0, bj = 1;
  for (int i = 0; i < n; ++i)
    for (int j = i + 1; j < n; ++j) {
      const double v = m(i, j);
      const bool less = v < best;
      best = less ? v : best;
      bi = less ? i : bi;
      bj = less ? j : bj;
    }
  return {bi, bj};
}

// Lobes whose merge changes nothing measurable: the same normal, length and roughness.
bool near_duplicates(const Lobe& a, const Lobe& b) {
  const glm::vec3 d = a.normal - b.normal;
  return glm::dot(d, d) < 1e-12f && std::abs(a.alpha2 - b.alpha2) <= 1e-4f * std::min(a.alpha2, b.alpha2) &&
         a.alpha2_hi == b.alpha2_hi && a.ggx == b.ggx && a.skirt == b.skirt;
}

}  // namespace

Lobe merge_lobes(const Lobe& a, const Lobe& b, float spread_scale) {
  if (!(double(a.weight) + b.weight > 0)) return a;
  const Summary sa = summarize(a), sb = summarize(b);
  Merged m = merge_pair(a, sa, b, sb, spread_scale, false);
  keep_specular_flux(std::array<Member, 2>{Member{&a, &sa}, Member{&b, &sb}}, m);
  return m.lobe;
}

int reduce_lobes(std::span<Lobe> lobes, int n, const ReductionOptions& options) {
  constexpr int kCap = 9 * kMaxLobes;
  n = std::min(n, std::min(kCap, static_cast<int>(lobes.size())));
  auto L = [&](int i) -> Lobe& { return lobes[static_cast<std::size_t>(i)]; };
  // Drop empty lobes; fold near-duplicates into the first of them (cheap, and exact to rounding).
  int k = 0;
  for (int i = 0; i < n; ++i) {
    if (!(L(i).weight > 0)) continue;
    int dup = -1;
    for (int j = 0; j < k && dup < 0; ++j)
      if (near_duplicates(L(j), L(i))) dup = j;
    if (dup >= 0) {
      const Summary sd = summarize(L(dup)), si = summarize(L(i));
      MergeBase mb = merge_base(std::array<Member, 2>{Member{&L(dup), &sd}, Member{&L(i), &si}});
      mb.lobe.alpha2 = L(dup).alpha2, mb.lobe.alpha2_hi = L(dup).alpha2_hi, mb.lobe.ggx = L(dup).ggx;
      mb.lobe.skirt = L(dup).skirt;
      L(dup) = mb.lobe;
    }
    else
      L(k++) = L(i);
  }
  n = k;
  const int max_lobes = std::clamp(options.max_lobes, 1, kMaxLobes);
  if (n > 1 && (n > max_lobes || options.tolerance > 0)) {
    // Per thread, not per call: 72 summaries would be zero-filled on every call otherwise.
    static thread_local std::array<Summary, kCap> sum;
    for (int i = 0; i < n; ++i) sum[static_cast<std::size_t>(i)] = summarize(L(i));
    auto S = [&](int i) -> const Summary& { return sum[static_cast<std::size_t>(i)]; };
    // Merges lobe bj into lobe bi; the last lobe takes bj's place, with its row of the pair matrix M
    // (the caller recomputes bi's row).
    // `known`: the pair's merge when the search made it already (its cost known), else null.
    auto merge_into = [&](int bi, int bj, auto& M, const Merged* known) {
      Merged m = known ? *known : merge_pair(L(bi), S(bi), L(bj), S(bj), options.spread_scale, false);
      keep_specular_flux(std::array<Member, 2>{Member{&L(bi), &S(bi)}, Member{&L(bj), &S(bj)}}, m);
      L(bi) = m.lobe;
      sum[static_cast<std::size_t>(bi)] = m.summary;
      const int last = n - 1;
      if (bj != last) {
        L(bj) = L(last);
        sum[static_cast<std::size_t>(bj)] = sum[static_cast<std::size_t>(last)];
        for (int i = 0; i < last; ++i)
          if (i != bj) M(i, bj) = M(i, last);
      }
      --n;
    };
    // The texel's own squared norm in the units of the cost, for the relative tolerance.
    std::array<Member, kCap> all;
    for (int i = 0; i < n; ++i) all[static_cast<std::size_t>(i)] = {&L(i), &S(i)};
    const std::span<const Member> whole(all.data(), static_cast<std::size_t>(n));
    const double spec_norm2 = union_spec_norm2(whole);
    double diffuse_amp = 0;
    for (int i = 0; i < n; ++i) diffuse_amp += S(i).weight * glm::length(glm::dvec3(L(i).normal)) * S(i).rho;
    const double norm2 = spec_norm2 + (4.0 / 3.0) * diffuse_amp * diffuse_amp;
    const double budget = double(options.tolerance) * options.tolerance * norm2;
    // Most texels of smooth regions end as one lobe: try that first, as one merge of the whole union
    // within the budget, before the pairwise search (which would take about n² merges to get there).
    if (budget > 0) {
      const UnionTerms terms{spec_norm2, horizon_sums(whole, union_weight(whole))};
      if (union_cost_bound(whole, terms.horizon) <= budget) {
        Merged m = merge_union(whole, &terms, options.spread_scale, kWholePeakWeight);
        if (m.cost <= budget) {
          keep_specular_flux(whole, m);
          L(0) = m.lobe;
          return 1;
        }
      }
    }
    double spent = 0;
    // Rough lobes only: the cheap distance takes the union down to max_lobes.
    bool all_rough = n > max_lobes;
    for (int i = 0; i < n && all_rough; ++i) all_rough = S(i).alpha2 >= kResolutionAlpha2;
    if (all_rough) {
      static thread_local std::array<double, kCap * kCap> dist;
      auto D = [&](int i, int j) -> double& { return dist[static_cast<std::size_t>(std::min(i, j) * kCap + std::max(i, j))]; };
      for (int i = 0; i < n; ++i)
        for (int j = i + 1; j < n; ++j) D(i, j) = rough_distance(S(i), S(j));
      while (n > max_lobes) {
        const auto [bi, bj] = cheapest_pair(n, D);
        merge_into(bi, bj, D, nullptr);
        for (int i = 0; i < n; ++i)
          if (i != bi) D(i, bi) = rough_distance(S(i), S(bi));
      }
    }
    // Pairwise merge costs, upper triangle, evaluated lazily: a pair holds a lower bound
    // (union_cost_bound) until it is the cheapest candidate, and only then its cost, so pairs that
    // can never be the cheapest, or never fit the budget, are never merged on trial. After a merge
    // only the merged lobe's row changes. The merges made are those of the eager greedy search.
    static thread_local std::array<double, kCap * kCap> cost;
    static thread_local std::array<bool, kCap * kCap> exact;
    // An exact pair's merge, kept so that the merge chosen is not made twice: `made` holds them in
    // the order made, `made_at` a pair's index into it (valid while the pair is exact).
    static thread_local std::vector<Merged> made;
    static thread_local std::array<std::uint16_t, kCap * kCap> made_at;
    made.clear();
    auto at = [](int i, int j) { return static_cast<std::size_t>(std::min(i, j) * kCap + std::max(i, j)); };
    auto C = [&](int i, int j) -> double& { return cost[at(i, j)]; };
    auto bound = [&](int i, int j) {
      const std::array<Member, 2> u{Member{&L(i), &S(i)}, Member{&L(j), &S(j)}};
      C(i, j) = union_cost_bound(u, horizon_sums(u, union_weight(u)));
      exact[at(i, j)] = false;
    };
    for (int i = 0; i < n; ++i)
      for (int j = i + 1; j < n; ++j) bound(i, j);
    // merge_into moves the last lobe's row of C into bj's; its flags move with it.
    auto merge_lazy = [&](int bi, int bj) {
      const int last = n - 1;
      const Merged* known = &made[made_at[at(bi, bj)]];
      if (bj != last)
        for (int i = 0; i < last; ++i)
          if (i != bj) exact[at(i, bj)] = exact[at(i, last)], made_at[at(i, bj)] = made_at[at(i, last)];
      merge_into(bi, bj, C, known);
    };
    while (n > 1) {
      int bi = 0, bj = 1;
      double best = INFINITY;
      for (;;) {
        std::tie(bi, bj) = cheapest_pair(n, C);
        best = C(bi, bj);
        if (exact[at(bi, bj)] || (n <= max_lobes && spent + best > budget)) break;
        made.push_back(merge_pair(L(bi), S(bi), L(bj), S(bj), options.spread_scale));
        made_at[at(bi, bj)] = static_cast<std::uint16_t>(made.size() - 1);
        C(bi, bj) = made.back().cost;
        exact[at(bi, bj)] = true;
      }
      if (n <= max_lobes) {
        if (spent + best > budget) break;
        spent += best;
      }
      merge_lazy(bi, bj);
      for (int i = 0; i < n; ++i)
        if (i != bi) bound(i, bi);
    }
  }
  std::sort(lobes.begin(), lobes.begin() + n, [](const Lobe& a, const Lobe& b) { return a.weight > b.weight; });
  return n;
}

}  // namespace svbrdf
