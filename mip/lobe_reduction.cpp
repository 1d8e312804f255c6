#include "mip/lobe_reduction.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <tuple>
#include <utility>
#include <vector>

#include "base/math.h"
#include "mip/albedo_table.h"
#include "mip/diffuse_transmission.h"
#include "mip/lobe_fit.h"
#include "mip/merge_cost.h"
#include "mip/reduction_numerics.h"
#include "mip/slope_stretch.h"

namespace svbrdf {

// The reduction itself: merging a union (merge_union: its linear parts, its two moments, its shape by
// lobe_fit.h, its cost by merge_cost.h), keeping the union's specular flux (albedo_table.h), and the
// greedy search over a texel's lobes (reduce_lobes).

namespace reduction {
namespace {

// The merged lobe but for its shape: the linear parts (weight, ρ, F0, mean normal).
struct MergeBase {
  Lobe lobe;
  Summary summary;  // all but the shape's
};

// The union's transmission stretch, which merge_union's stretch of the reflection is not: a thin wall's
// transmission is its texels' shapes untilted (lobe.h "Transmission"), so its slopes spread as the
// amplitude-weighted mean of the members' α_T²·S_T alone, without the 2·ττᵀ of their normals' offsets
// (slope_stretch.h). Sets m's transmission stretch to it and takes the tail sum in its frame, each
// member's A·tr(S_m⁻¹·S_k)/2 as merge_union takes the reflection's; the peaks are unchanged.
void transmission_stretch(std::span<const Member> u, Lobe& m, double& t_tail) {
  Sym2 spread{0, 0, 0};
  const auto amplitude = [](const Lobe& l) {
    return double(l.weight) * (double(l.transmission.r) + l.transmission.g + l.transmission.b);
  };
  for (const Member& x : u) {
    const double a = amplitude(*x.lobe);
    if (!(a > 0) || !(x.lobe->transmission_alpha2 > 0)) continue;
    const Sym2 s = transmission_stretch_matrix(*x.lobe);
    const double k = a * transmission_moments(*x.lobe).tail;
    spread.xx += k * s.xx, spread.xy += k * s.xy, spread.yy += k * s.yy;
  }
  set_stretch(m.transmission_stretch, m.transmission_stretch_dir, spread);
  const Sym2 s_inv = transmission_stretch_matrix(m).inverse_det1();
  double w = 0;
  for (const Member& x : u) w += x.lobe->weight;
  t_tail = 0;
  for (const Member& x : u) {
    const double a = amplitude(*x.lobe) / w;
    if (!(a > 0) || !(x.lobe->transmission_alpha2 > 0)) continue;
    t_tail += a * transmission_moments(*x.lobe).tail * 0.5 * trace_of_product(s_inv, transmission_stretch_matrix(*x.lobe));
  }
}

MergeBase merge_base(std::span<const Member> u) {
  MergeBase mb;
  Lobe& m = mb.lobe;
  double w = 0;
  for (const Member& x : u) w += x.lobe->weight;
  // Shares by one reciprocal: this runs for every candidate merge of every texel.
  const double inv_w = 1.0 / w;
  glm::dvec3 diffuse(0), f0(0), f0_tint(0), diffuse90(0), transmission(0), transmission90(0), nbar(0);
  glm::dvec3 dtrans(0), dtrans90(0);  // the diffuse transmission's τd and τd90 (diffuse_transmission.h)
  double f90 = 0, coat = 0, sheen = 0;
  double t_amp = 0, t_tail = 0, t_peak = 0;  // the transmission's amplitude and its moments' sums (below)
  bool t_stretched = false;                   // some member's transmission is stretched
  bool plain = true;  // every member's F90 is 1: the mean is 1 exactly, not a rounding of it
  Summary& s = mb.summary;
  s.rho = s.f0 = 0;
  for (const Member& x : u) {
    const double t = x.lobe->weight * inv_w;
    diffuse += t * glm::dvec3(x.lobe->diffuse);
    f0 += t * glm::dvec3(x.lobe->f0);
    f0_tint += t * glm::dvec3(x.lobe->f0_tint);
    diffuse90 += t * glm::dvec3(x.lobe->diffuse90);
    transmission += t * glm::dvec3(x.lobe->transmission);
    transmission90 += t * glm::dvec3(x.lobe->transmission90);
    dtrans += t * glm::dvec3(x.lobe->diffuse_transmission);
    dtrans90 += t * glm::dvec3(x.lobe->diffuse_transmission90);
    const double a = t * (double(x.lobe->transmission.r) + x.lobe->transmission.g + x.lobe->transmission.b);
    if (a > 0 && x.lobe->transmission_alpha2 > 0) {
      const TransmissionMoments tm = transmission_moments(*x.lobe);
      t_amp += a, t_tail += a * tm.tail, t_peak += a * tm.peak;
      if (x.lobe->transmission_stretch > 1.0f) t_stretched = true;
    }
    f90 += t * x.lobe->f90;
    coat += t * x.lobe->coat;
    sheen += t * x.lobe->sheen;
    plain = plain && x.lobe->f90 == 1.0f;
    nbar += t * glm::dvec3(x.lobe->normal);
    s.rho += t * x.sum->rho;
    s.f0 += t * x.sum->f0;
  }
  m.weight = static_cast<float>(w);
  m.diffuse = glm::vec3(diffuse);
  m.f0 = glm::vec3(f0);
  m.f0_tint = glm::vec3(f0_tint);
  m.diffuse90 = glm::vec3(diffuse90);
  m.transmission = glm::vec3(transmission);
  m.transmission90 = glm::vec3(transmission90);
  m.diffuse_transmission = glm::vec3(dtrans);
  m.diffuse_transmission90 = glm::vec3(dtrans90);
  // The members transmit about −wo whatever their normals' tilts (a thin wall passes light straight
  // through; lobe.h "Transmission"), so the union's transmission is their shapes untilted: the shape of
  // their amplitude-weighted tail and peak moments.
  if (t_stretched) transmission_stretch(u, m, t_tail);
  if (t_amp > 0) set_transmission_shape(m, t_tail / t_amp, t_peak / t_amp);
  m.coat = static_cast<float>(coat);
  m.sheen = static_cast<float>(sheen);
  if (plain) f90 = 1.0;
  m.f90 = static_cast<float>(f90);
  s.f90 = f90;
  m.normal = glm::vec3(nbar);
  const double len = glm::length(nbar);
  s.n = len > 0 ? nbar * (1.0 / len) : glm::dvec3(0, 0, 1);
  s.weight = w;
  s.amp = specular_amp(w, len, s.f0, s.f90);
  return mb;
}

// The merged lobe of a union, with its summary and estimated cost.
struct Merged {
  Lobe lobe;
  Summary summary;
  double cost = 0;
};

// Merges the union u; returns the merged lobe, its summary and, when the union's terms are given (a
// candidate merge, not one already chosen), its cost, with `peak_weight` on its highlight term (the
// options' for pairs; the whole-union try has its own, merge_cost.h).
Merged merge_union(std::span<const Member> u, const UnionTerms* terms, const ReductionOptions& o, double peak_weight) {
  const MergeBase mb = merge_base(u);
  double K = 0;
  for (const Member& x : u) K += x.sum->amp;
  const bool by_amp = K > 0;
  if (!by_amp)
    for (const Member& x : u) K += x.sum->weight;
  const glm::dvec3& n = mb.summary.n;
  // A union with a stretched member gets a stretch, and its moments below are taken in that stretch's
  // frame (slope_stretch.h); a union of isotropic lobes takes none of this.
  bool stretched = false;
  for (const Member& x : u) stretched = stretched || x.sum->stretched;
  Lobe stretch_of;  // the merged stretch, set on the merged lobe after its shape
  Sym2 s_inv;       // S_m⁻¹
  glm::dvec2 slope_m(0.0);
  if (stretched) {
    slope_m = normal_slope(n);
    Sym2 spread{0, 0, 0};
    for (const Member& x : u) {
      const Summary& a = *x.sum;
      const double k = (by_amp ? a.amp : a.weight) / K;
      const glm::dvec2 tau = a.slope - slope_m;
      spread.xx += k * (a.tail * a.stretch.xx + 2 * tau.x * tau.x);
      spread.xy += k * (a.tail * a.stretch.xy + 2 * tau.x * tau.y);
      spread.yy += k * (a.tail * a.stretch.yy + 2 * tau.y * tau.y);
    }
    set_stretch(stretch_of, spread);
    s_inv = stretch_matrix(stretch_of).inverse_det1();
  }
  // A member's tan²θ to the merged normal in the merged stretch's frame (`own`: in its own stretch's,
  // for its D there). The union's cone mass below (the skirt's and the atom's fits, lobe_fit.h) stays
  // isotropic: the cone is the LOD camera's, round about the merged normal.
  const auto tilt2 = [&](const Summary& a, bool own) {
    const double t = tan2_between(a.n, n);
    if (!stretched || !std::isfinite(t)) return t;
    const glm::dvec2 tau = a.slope - slope_m;
    return own ? a.stretch.inverse_det1().quad(tau) : s_inv.quad(tau);
  };
  // The union's π·D at the merged normal, and its mass within slope radius² R² of it (each per unit of
  // K, as A and P below; lobe_fit.h).
  const auto union_centre = [&] {
    double centre = 0;
    for (const Member& x : u) {
      const Summary& a = *x.sum;
      centre += (by_amp ? a.amp : a.weight) * kPiD * d_at_tan2(a.d_shape, tilt2(a, true));
    }
    return centre / K;
  };
  const UnionMass union_mass{u, n, by_amp, K};
  // Moments of the union about the merged normal: the tails add (A), and each lobe's peak, widened
  // by its tilt to the merged normal (LEAN: α² + tan²θ, Olano & Baker 2010), adds (P_lean). When A and
  // that P make a spread core (A·P < 1: narrow lobes spread by their normals), P_lean overestimates
  // the union's centre (by about ln(2σ²/α²) for a Gaussian spread σ) and the error compounds over the
  // levels (+8 % at granite's mirror pairs by level 8); the union's exact D at the merged normal
  // (P_centre) alone underestimates it for the next level (−9 %: the union's core is flatter than a
  // spread core's). The spread core takes a blend, lean_peak_share_spread of P_lean; a roughness
  // mixture keeps P_lean for its band (a blend there moved metal-tray's off-specular level means by
  // 5–7 %), and so does its atom where it gets one (set_shape; P_centre there raised polished granite's
  // highlight by 2–3 % and lowered the tray's glow under a 45° sun by 1–2 %; docs/mip-algorithm.md, §4.1).
  double A = 0, P_lean = 0;
  for (const Member& x : u) {
    const Summary& a = *x.sum;
    const double k = by_amp ? a.amp : a.weight;
    const double t = std::min(tilt2(a, false), 1e3);
    A += k * a.tail * (stretched ? 0.5 * trace_of_product(s_inv, a.stretch) : 1.0);
    P_lean += k / (1.0 / a.peak + o.spread_scale * t);
  }
  double P = P_lean;
  const double lean = o.lean_peak_share_spread;
  if (A * P_lean < K * K) P = (1.0 - lean) * union_centre() * K + lean * P_lean;
  // A spread core narrower than a few degrees gets a skirt fitted to the union's mass in the cone of
  // kSkirtTan2 (set_shape): with its peak and tail kept, a one-width core puts into that cone the
  // mass the union spreads just outside it (texels tilted by 1–3°), +2 to +3.5 % on polished granite's
  // highlight from level 5 on. Wider cores (the tile roof's slopes, honed granite) keep c = 1: their
  // unions have no such shoulder, and slopes stop adding at their tilts (docs/mip-algorithm.md, §4.3).
  // A roughness mixture whose union is sharper at its centre than a log-uniform band gets an atom,
  // fitted to the union's mass within the core (set_shape).
  Merged best{mb.lobe, mb.summary, 0};
  set_shape(best.lobe, A / K, P / K, &union_mass);
  best.lobe.stretch = stretch_of.stretch;
  best.lobe.stretch_dir = stretch_of.stretch_dir;
  best.summary = summarize(best.lobe);
  if (terms) best.cost = union_cost(u, *terms, best.summary, by_amp, peak_weight);
  return best;
}

Merged merge_pair(const Lobe& a, const Summary& sa, const Lobe& b, const Summary& sb, const ReductionOptions& o,
                  bool with_cost = true) {
  const std::array<Member, 2> u{Member{&a, &sa}, Member{&b, &sb}};
  if (!with_cost) return merge_union(u, nullptr, o, o.peak_weight);
  const UnionTerms terms = union_terms(u);
  return merge_union(u, &terms, o, o.peak_weight);
}

// Keeps the union's specular albedo: scales the merged lobe's weight (which scales its specular part)
// and divides its ρ and ρ90, and its diffuse transmission's τd and τd90, by the same factor (which
// leaves its diffuse parts as they were: weight·ρ and weight·τd the union's means); then scales
// its τ and τ90 so that it transmits what the union transmits (transmission_flux: its transmission
// shape is not its reflection's, merge_base), and its τd and τd90 so that it transmits diffusely what
// the union does (diffuse_transmission_flux). Applied when a merge is made, not while costs are
// estimated (it changes them by a few percent of the amplitude only).
void keep_specular_flux(std::span<const Member> u, Merged& m) {
  // A lobe made by an earlier merge knows its flux (it was set to keep its lobes' there).
  double want = 0;
  for (const Member& x : u) want += x.sum->flux >= 0 ? x.sum->flux : specular_flux(*x.lobe);
  const double have = specular_flux(m.lobe);
  m.summary.flux = have;
  if (have > 0 && want > 0) {
    const double scale = want / have;
    m.lobe.weight = static_cast<float>(m.lobe.weight * scale);
    m.lobe.diffuse = glm::vec3(glm::dvec3(m.lobe.diffuse) / scale);
    m.lobe.diffuse90 = glm::vec3(glm::dvec3(m.lobe.diffuse90) / scale);
    if (diffuse_transmits(m.lobe)) {
      m.lobe.diffuse_transmission = glm::vec3(glm::dvec3(m.lobe.diffuse_transmission) / scale);
      m.lobe.diffuse_transmission90 = glm::vec3(glm::dvec3(m.lobe.diffuse_transmission90) / scale);
    }
    // What of the summary the weight and ρ enter (its shape is unchanged).
    const double len = glm::length(glm::dvec3(m.lobe.normal));
    m.summary.weight = m.lobe.weight;
    m.summary.rho = mean3(m.lobe.diffuse);
    m.summary.f0 = mean3(m.lobe.f0);
    m.summary.amp = specular_amp(m.lobe.weight, len, m.summary.f0, m.summary.f90);
    m.summary.flux = want;
  }
  if (diffuse_transmits(m.lobe)) {
    glm::dvec3 want_d(0);
    for (const Member& x : u) want_d += diffuse_transmission_flux(*x.lobe);
    const glm::dvec3 have_d = diffuse_transmission_flux(m.lobe);
    for (int c = 0; c < 3; ++c)
      if (have_d[c] > 0 && want_d[c] > 0) {
        const double scale = want_d[c] / have_d[c];
        m.lobe.diffuse_transmission[c] = static_cast<float>(m.lobe.diffuse_transmission[c] * scale);
        m.lobe.diffuse_transmission90[c] = static_cast<float>(m.lobe.diffuse_transmission90[c] * scale);
      }
  }
  if (transmits(m.lobe)) {
    double want_t = 0;
    for (const Member& x : u) want_t += transmission_flux(*x.lobe);
    const double have_t = transmission_flux(m.lobe);
    if (have_t > 0 && want_t > 0) {
      const double scale = want_t / have_t;
      m.lobe.transmission = glm::vec3(glm::dvec3(m.lobe.transmission) * scale);
      m.lobe.transmission90 = glm::vec3(glm::dvec3(m.lobe.transmission90) * scale);
    }
  }
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
         a.alpha2_hi == b.alpha2_hi && a.ggx == b.ggx && a.skirt == b.skirt && a.stretch == b.stretch &&
         (a.stretch == 1.0f || a.stretch_dir == b.stretch_dir);
}

}  // namespace
}  // namespace reduction

void set_transmission_shape(Lobe& l, double tail, double peak) {
  const double k = std::sqrt(tail * peak);
  if (!(k > 1.0 + 1e-6)) {
    l.transmission_alpha2 = static_cast<float>(1.0 / peak);
    l.transmission_alpha2_hi = 0.0f;
    return;
  }
  double x = std::sqrt(6.0 * (k - 1.0));
  for (int i = 0; i < 60; ++i) {
    const double sh = std::sinh(x), f = sh / x - k, df = (std::cosh(x) * x - sh) / (x * x);
    const double step = f / df;
    x -= step;
    if (!(step > 1e-12 * x)) break;
  }
  const double g = std::sqrt(tail / peak);
  l.transmission_alpha2 = static_cast<float>(g * std::exp(-x));
  l.transmission_alpha2_hi = static_cast<float>(g * std::exp(x));
}

Lobe merge_lobes(const Lobe& a, const Lobe& b, float spread_scale) {
  using namespace reduction;
  if (!(double(a.weight) + b.weight > 0)) return a;
  const Summary sa = summarize(a), sb = summarize(b);
  ReductionOptions o;
  o.spread_scale = spread_scale;
  Merged m = merge_pair(a, sa, b, sb, o, false);
  keep_specular_flux(std::array<Member, 2>{Member{&a, &sa}, Member{&b, &sb}}, m);
  return m.lobe;
}

int reduce_lobes(std::span<Lobe> lobes, int n, const ReductionOptions& options) {
  using namespace reduction;
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
      mb.lobe.stretch = L(dup).stretch, mb.lobe.stretch_dir = L(dup).stretch_dir;
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
      Merged m = known ? *known : merge_pair(L(bi), S(bi), L(bj), S(bj), options, false);
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
    const double trans_norm2 = union_trans_norm2(whole);
    const double norm2 = spec_norm2 + (4.0 / 3.0) * diffuse_amp * diffuse_amp + trans_norm2;
    const double budget = double(options.tolerance) * options.tolerance * norm2;
    // Most texels of smooth regions end as one lobe: try that first, as one merge of the whole union
    // within the budget, before the pairwise search (which would take about n² merges to get there).
    if (budget > 0) {
      const UnionTerms terms{spec_norm2, horizon_sums(whole, union_weight(whole)), trans_norm2};
      if (union_cost_bound(whole, terms.horizon) <= budget) {
        Merged m = merge_union(whole, &terms, options, kWholePeakWeight);
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
        made.push_back(merge_pair(L(bi), S(bi), L(bj), S(bj), options));
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
