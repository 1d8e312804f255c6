#include "mip/lobe_reduction.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace svbrdf {

namespace {

constexpr double kPi = 3.14159265358979323846;

// The resolution below which the cost model stops telling specular lobes apart: every lobe is seen
// blurred by a GGX-like kernel of α² = kResolutionAlpha2 (α = 0.1, about 6°, the scale of the metric's
// direction grid). Without it the L2 norm of a lobe grows as 1/α², so the shape differences of
// mirror-like lobes (α ≈ 0.005 against 0.01) would outweigh everything else and a polished tray's
// soft fingerprint glow would be merged away to keep them apart.
constexpr double kResolutionAlpha2 = 0.01;
// The weight of the highlight-peak term of merge_cost (see there).
constexpr double kPeakWeight = 1.0;

double mean3(const glm::vec3& c) { return (double(c.x) + c.y + c.z) / 3.0; }

// What the cost model needs of a lobe, computed once per lobe.
struct Summary {
  glm::dvec3 n{0, 0, 1};  // unit normal
  double weight = 0;
  double amp = 0;     // specular amplitude: its share of the reflected flux
  double d_z = 0;     // GGX D at h = z (the geometric normal)
  double rho = 0;     // mean diffuse albedo
  double f0 = 0;      // mean F0
  double alpha2 = 1;
};

Summary summarize(const Lobe& l) {
  Summary s;
  const glm::dvec3 nbar(l.normal);
  const double len = glm::length(nbar);
  s.n = len > 0 ? nbar / len : glm::dvec3(0, 0, 1);
  s.weight = l.weight;
  s.rho = mean3(l.diffuse);
  s.f0 = mean3(l.f0);
  // F0 plus a little for Fresnel's rise toward grazing angles; len: the lobe's cosine factor.
  s.amp = double(l.weight) * len * (s.f0 + 0.05 * (1.0 - s.f0));
  s.alpha2 = l.alpha2;
  const double c = s.n.z;
  if (c > 0) {
    const double sin2 = s.n.x * s.n.x + s.n.y * s.n.y;
    const double d = sin2 + c * c * s.alpha2;
    s.d_z = s.alpha2 / (kPi * d * d);
  }
  return s;
}

// tan²θ between two unit vectors (∞ at or past 90°).
double tan2_between(const glm::dvec3& a, const glm::dvec3& b) {
  const double c = glm::dot(a, b);
  if (c <= 1e-6) return INFINITY;
  return std::max(0.0, 1.0 / (c * c) - 1.0);
}

// The L2 inner product, over (wi, wo) pairs, of two specular lobes of amplitude 1: each lobe's
// reflected radiance around its mirror direction approximated by a Gaussian of per-axis variance
// 2α² (the half vector's α²/2, doubled twice by the mirror map), their centres 2·tanθ apart.
// ∫ N(x; μa, Σa) N(x; μb, Σb) dx = N(μa − μb; 0, Σa + Σb) gives exp(−d²/(αa² + αb²)) / (4π(αa² + αb²)),
// times the 2π of wi; both lobes blurred to the resolution kResolutionAlpha2.
double spec_inner(double alpha2_a, double alpha2_b, double tan2) {
  if (!std::isfinite(tan2)) return 0.0;
  const double s = alpha2_a + alpha2_b + 2.0 * kResolutionAlpha2;
  return std::exp(-tan2 / s) / (2.0 * s);
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
  double albedo(double alpha2, double f0) const {
    const double x = (std::log(std::clamp(alpha2, kMin, 1.0)) - std::log(kMin)) / (-std::log(kMin)) * (kSize - 1);
    const int i = std::min(kSize - 2, static_cast<int>(x));
    const double t = x - i;
    const auto at = [&](const std::array<double, kSize>& v) { return v[static_cast<std::size_t>(i)] * (1 - t) + v[static_cast<std::size_t>(i + 1)] * t; };
    return f0 * at(a_) + (1 - f0) * at(b_);
  }

 private:
  static constexpr int kSize = 128;
  static constexpr double kMin = 1e-6;
  SpecAlbedoTable() {
    constexpr int n = 64;
    for (int k = 0; k < kSize; ++k) {
      const double a2 = std::exp(std::log(kMin) * (1.0 - double(k) / (kSize - 1)));
      double sa = 0, sb = 0;
      for (double theta : {0.0, 45.0, 75.0}) {
        const glm::dvec3 wi(std::sin(theta * kPi / 180), 0, std::cos(theta * kPi / 180));
        for (int p = 0; p < n; ++p)
          for (int q = 0; q < n; ++q) {
            // h with density D(h)·cosθh: tan²θh = α²·u/(1 − u) (Walter et al. 2007); then
            // f·wo.z/pdf(wo) with pdf(wo) = D·cosθh/(4·wo·h), so D cancels.
            const double u = (p + 0.5) / n, phi = 2 * kPi * (q + 0.5) / n;
            const double c = 1 / std::sqrt(1 + a2 * u / (1 - u)), sn = std::sqrt(std::max(0.0, 1 - c * c));
            const glm::dvec3 h(sn * std::cos(phi), sn * std::sin(phi), c);
            const double oh = glm::dot(wi, h);
            const glm::dvec3 wo = 2 * oh * h - wi;
            if (wo.z <= 0 || oh <= 0) continue;
            const double vis = 0.5 / (wo.z * std::sqrt(a2 + (1 - a2) * wi.z * wi.z) + wi.z * std::sqrt(a2 + (1 - a2) * wo.z * wo.z));
            const double x = 1 - oh, w = x * x * x * x * x;
            const double g = 4 * vis * wo.z * oh / c;
            sa += g;      // F0 = 1: F = 1
            sb += g * w;  // F0 = 0: F = w
          }
      }
      a_[static_cast<std::size_t>(k)] = sa / (n * n);
      b_[static_cast<std::size_t>(k)] = sb / (n * n);
    }
  }
  std::array<double, kSize> a_{}, b_{};
};

// The estimated squared error of replacing lobes a and b by m, without the peak term.
double shape_cost(const Summary& a, const Summary& b, const Summary& m) {
  const double Am = a.amp + b.amp;
  const double tab = tan2_between(a.n, b.n), tam = tan2_between(a.n, m.n), tbm = tan2_between(b.n, m.n);
  const double spec = a.amp * a.amp * spec_inner(a.alpha2, a.alpha2, 0) + b.amp * b.amp * spec_inner(b.alpha2, b.alpha2, 0) +
                      Am * Am * spec_inner(m.alpha2, m.alpha2, 0) + 2 * a.amp * b.amp * spec_inner(a.alpha2, b.alpha2, tab) -
                      2 * Am * a.amp * spec_inner(m.alpha2, a.alpha2, tam) - 2 * Am * b.amp * spec_inner(m.alpha2, b.alpha2, tbm);
  // Horizons: the linear part of the cosine factors is kept exactly, but where the lobes' horizons
  // differ (a lune of width δ, the angle between the normals) the merged lobe's smooth horizon
  // differs from theirs; diffuse and grazing specular (Fresnel rises toward 1) both feel it. Plus
  // the coupling of color and normal (ρ̄·n̄ ≠ E[ρ·n]).
  const double w = a.weight + b.weight, ab = a.weight * b.weight / w;
  const double cos_ab = std::clamp(glm::dot(a.n, b.n), -1.0, 1.0);
  const double delta = glm::length(a.n - b.n);  // the angle between the normals, to O(δ³)
  const double horizon_amp = m.rho + m.f0 + 0.2 * (1.0 - m.f0);
  const double drho = a.rho - b.rho;
  const double horizon = ab * 0.4 * horizon_amp * horizon_amp * delta + (4.0 / 3.0) * ab * ab * drho * drho * 2.0 * (1.0 - cos_ab);
  return std::max(0.0, spec) + horizon;
}

// The full cost: the shape cost plus the highlight about the geometric normal. Every mirror pair of
// the metric has h = z, and a polished surface seen from afar shows its highlight there, so a merge
// that lowers or raises the mixture's peak at h = z is charged for it (the blurred L2 above cannot
// see the height of narrow peaks).
double peak_cost(const Summary& a, const Summary& b, const Summary& m) {
  const double peak = a.amp * a.d_z + b.amp * b.d_z - (a.amp + b.amp) * m.d_z;
  return kPeakWeight * peak * peak;
}
double full_cost(const Summary& a, const Summary& b, const Summary& m) { return shape_cost(a, b, m) + peak_cost(a, b, m); }

// The merged lobe but for its α²: the linear parts (weight, ρ, F0, mean normal) and the spread of the
// two normals about the merged one in slope space (α² = 2σ², LEAN), weighted by the lobes' specular
// amplitudes (their share of the highlight).
struct MergeBase {
  Lobe lobe;
  Summary summary;  // all but alpha2 and d_z
  double spread = 0;
};

MergeBase merge_base(const Lobe& a, const Summary& sa, const Lobe& b, const Summary& sb, float spread_scale) {
  MergeBase mb;
  Lobe& m = mb.lobe;
  const double wa = a.weight, wb = b.weight, w = wa + wb;
  // Shares instead of divisions: this runs for every candidate pair of every texel.
  const double ta_ = wa / w, tb_ = wb / w;
  m.weight = static_cast<float>(w);
  m.diffuse = glm::vec3(ta_ * glm::dvec3(a.diffuse) + tb_ * glm::dvec3(b.diffuse));
  m.f0 = glm::vec3(ta_ * glm::dvec3(a.f0) + tb_ * glm::dvec3(b.f0));
  const glm::dvec3 nbar = ta_ * glm::dvec3(a.normal) + tb_ * glm::dvec3(b.normal);
  m.normal = glm::vec3(nbar);
  const double len = glm::length(nbar);
  Summary& s = mb.summary;
  s.n = len > 0 ? nbar * (1.0 / len) : glm::dvec3(0, 0, 1);
  s.weight = w;
  s.rho = ta_ * sa.rho + tb_ * sb.rho;
  s.f0 = ta_ * sa.f0 + tb_ * sb.f0;
  s.amp = w * len * (s.f0 + 0.05 * (1.0 - s.f0));
  double ka = sa.amp, kb = sb.amp;
  if (!(ka + kb > 0)) ka = wa, kb = wb;
  const double ta = std::min(tan2_between(sa.n, s.n), 1e3), tb = std::min(tan2_between(sb.n, s.n), 1e3);
  mb.spread = spread_scale * (ka * ta + kb * tb) / (ka + kb);
  return mb;
}

// Completes a merge with the α² base chosen.
void set_alpha2(Lobe& m, Summary& s, double alpha2) {
  m.alpha2 = static_cast<float>(std::clamp(alpha2, 1e-6, 1.0));
  s.alpha2 = m.alpha2;
  const double c = s.n.z;
  s.d_z = 0;
  if (c > 0) {
    const double d = s.n.x * s.n.x + s.n.y * s.n.y + c * c * s.alpha2;
    s.d_z = s.alpha2 / (kPi * d * d);
  }
}

// Merges a and b; returns the merged lobe and its summary and cost.
struct Merged {
  Lobe lobe;
  Summary summary;
  double cost = 0;
};

Merged merge_pair(const Lobe& a, const Summary& sa, const Lobe& b, const Summary& sb, float spread_scale) {
  const MergeBase mb = merge_base(a, sa, b, sb, spread_scale);
  double ka = sa.amp, kb = sb.amp;
  if (!(ka + kb > 0)) ka = sa.weight, kb = sb.weight;
  const double xa = sa.alpha2, xb = sb.alpha2;
  // Similar roughness: the amplitude-weighted harmonic mean of α² keeps the height of the highlight
  // (a GGX peak is ∝ amplitude/α²) and the weights keep its flux. Dissimilar roughness: the harmonic
  // mean would turn a broad lobe into a spike, so of the harmonic mean, the arithmetic mean (second
  // moments) and the dominant lobe's α², the one with the lowest shape cost wins.
  Merged best{mb.lobe, mb.summary, 0};
  set_alpha2(best.lobe, best.summary, (ka + kb) / (ka / xa + kb / xb) + mb.spread);
  double best_shape = shape_cost(sa, sb, best.summary);
  if (std::max(xa, xb) > 4.0 * std::min(xa, xb)) {
    for (double base : {(ka * xa + kb * xb) / (ka + kb), ka >= kb ? xa : xb}) {
      Merged c{mb.lobe, mb.summary, 0};
      set_alpha2(c.lobe, c.summary, base + mb.spread);
      const double sc = shape_cost(sa, sb, c.summary);
      if (sc < best_shape) best_shape = sc, best = c;
    }
  }
  best.cost = best_shape + peak_cost(sa, sb, best.summary);
  return best;
}

// Keeps the pair's specular albedo: scales the merged lobe's weight (which scales its specular part)
// and divides its ρ by the same factor (which leaves its diffuse part as it was). Applied when a merge
// is made, not while costs are estimated (it changes them by a few percent of the amplitude only).
void keep_specular_flux(const Lobe& a, const Lobe& b, Merged& m) {
  const SpecAlbedoTable& t = SpecAlbedoTable::get();
  auto albedo = [&](const Lobe& l) { return double(l.weight) * glm::length(glm::dvec3(l.normal)) * t.albedo(l.alpha2, mean3(l.f0)); };
  const double want = albedo(a) + albedo(b), have = albedo(m.lobe);
  if (have > 0 && want > 0) {
    const double scale = want / have;
    m.lobe.weight = static_cast<float>(m.lobe.weight * scale);
    m.lobe.diffuse = glm::vec3(glm::dvec3(m.lobe.diffuse) / scale);
    m.summary = summarize(m.lobe);
  }
}

// For unions of rough lobes only (α² at or above the resolution, where shapes are smooth and no peak
// needs keeping): a cheap stand-in for full_cost that orders the merges down to max_lobes the same
// way on the presets (bench/results/mip.md) at a tenth of the cost — Ward's criterion (the product of
// the weights over their sum) times the squared distance of the shapes (log-roughness, the normals'
// offset relative to the lobes' widths) scaled by the specular amplitude's L2 norm, plus the horizon
// term of shape_cost.
double rough_distance(const Summary& a, const Summary& b) {
  const double w = a.weight + b.weight;
  const double ab = a.weight * b.weight / w;
  const double width = a.alpha2 + b.alpha2 + 2.0 * kResolutionAlpha2;
  const double amp = (a.amp + b.amp) / w;
  const glm::dvec3 dn = a.n - b.n;
  const double dn2 = glm::dot(dn, dn);
  const double dl = std::log(a.alpha2 / b.alpha2);
  const double rho = 0.5 * (a.rho + b.rho), f0 = 0.5 * (a.f0 + b.f0);
  const double horizon_amp = rho + f0 + 0.2 * (1.0 - f0);
  const double drho = a.rho - b.rho;
  return ab * (amp * amp / (2.0 * width) * (0.25 * dl * dl + dn2 / width) + 0.4 * horizon_amp * horizon_amp * std::sqrt(dn2)) +
         (4.0 / 3.0) * ab * ab * drho * drho * dn2;
}

// Lobes whose merge changes nothing measurable: the same normal, length and roughness.
bool near_duplicates(const Lobe& a, const Lobe& b) {
  const glm::vec3 d = a.normal - b.normal;
  return glm::dot(d, d) < 1e-12f && std::abs(a.alpha2 - b.alpha2) <= 1e-4f * std::min(a.alpha2, b.alpha2);
}

}  // namespace

Lobe merge_lobes(const Lobe& a, const Lobe& b, float spread_scale) {
  if (!(double(a.weight) + b.weight > 0)) return a;
  Merged m = merge_pair(a, summarize(a), b, summarize(b), spread_scale);
  keep_specular_flux(a, b, m);
  return m.lobe;
}

double merge_cost(const Lobe& a, const Lobe& b, const Lobe& merged) {
  return full_cost(summarize(a), summarize(b), summarize(merged));
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
      MergeBase mb = merge_base(L(dup), summarize(L(dup)), L(i), summarize(L(i)), 0.0f);
      set_alpha2(mb.lobe, mb.summary, L(dup).alpha2);
      L(dup) = mb.lobe;
    }
    else
      L(k++) = L(i);
  }
  n = k;
  const int max_lobes = std::clamp(options.max_lobes, 1, kMaxLobes);
  if (n > 1 && (n > max_lobes || options.tolerance > 0)) {
    std::array<Summary, kCap> sum;
    for (int i = 0; i < n; ++i) sum[static_cast<std::size_t>(i)] = summarize(L(i));
    auto S = [&](int i) -> const Summary& { return sum[static_cast<std::size_t>(i)]; };
    // Merges lobe bj into lobe bi; the last lobe takes bj's place, with its row of the pair matrix M
    // (the caller recomputes bi's row).
    auto merge_into = [&](int bi, int bj, auto& M) {
      Merged m = merge_pair(L(bi), S(bi), L(bj), S(bj), options.spread_scale);
      keep_specular_flux(L(bi), L(bj), m);
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
    double norm2 = 0, diffuse_amp = 0;
    for (int i = 0; i < n; ++i) {
      diffuse_amp += S(i).weight * glm::length(glm::dvec3(L(i).normal)) * S(i).rho;
      for (int j = 0; j < n; ++j) norm2 += S(i).amp * S(j).amp * spec_inner(S(i).alpha2, S(j).alpha2, tan2_between(S(i).n, S(j).n));
    }
    norm2 += (4.0 / 3.0) * diffuse_amp * diffuse_amp;
    const double budget = double(options.tolerance) * options.tolerance * norm2;
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
        int bi = 0, bj = 1;
        double best = INFINITY;
        for (int i = 0; i < n; ++i)
          for (int j = i + 1; j < n; ++j)
            if (D(i, j) < best) best = D(i, j), bi = i, bj = j;
        merge_into(bi, bj, D);
        for (int i = 0; i < n; ++i)
          if (i != bi) D(i, bi) = rough_distance(S(i), S(bi));
      }
    }
    // Pairwise merge costs, upper triangle; after a merge only the merged lobe's row changes.
    static thread_local std::array<double, kCap * kCap> cost;
    auto C = [&](int i, int j) -> double& { return cost[static_cast<std::size_t>(std::min(i, j) * kCap + std::max(i, j))]; };
    auto compute = [&](int i, int j) { C(i, j) = merge_pair(L(i), S(i), L(j), S(j), options.spread_scale).cost; };
    for (int i = 0; i < n; ++i)
      for (int j = i + 1; j < n; ++j) compute(i, j);
    while (n > 1) {
      int bi = 0, bj = 1;
      double best = INFINITY;
      for (int i = 0; i < n; ++i)
        for (int j = i + 1; j < n; ++j)
          if (C(i, j) < best) best = C(i, j), bi = i, bj = j;
      if (n <= max_lobes) {
        if (spent + best > budget) break;
        spent += best;
      }
      merge_into(bi, bj, C);
      for (int i = 0; i < n; ++i)
        if (i != bi) compute(i, bi);
    }
  }
  std::sort(lobes.begin(), lobes.begin() + n, [](const Lobe& a, const Lobe& b) { return a.weight > b.weight; });
  return n;
}

}  // namespace svbrdf
