#include "mip/lobe_fit.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "base/series_log.h"
#include "mip/reduction_numerics.h"

namespace svbrdf::reduction {

namespace {

// The cone a spread core's skirt is fitted in: the mass of D within 2.82° of the merged normal, the
// disc of the area of the ±2.5° square of half vectors that a 10° field of view spans (the LOD scenes'
// camera, whose images integrate D over that square). The resolution at which the skirt keeps the
// union's shape, as kResolutionAlpha2 is the cost's; the disc of equal area kept polished granite's
// highlight closer than the square's inscribed one (docs/mip-algorithm.md, §4.3 and §9).
constexpr double kSkirtTan2 = 0.0024279912;  // tan²(2.8209°), 2.8209° = √(25/π)°
// Cores get a skirt while P·kSkirtTan2 exceeds this (α² below 2.5·kSkirtTan2: a core within ~4.5°).
constexpr double kSkirtMinPeak = 0.4;

// Where a log-uniform band's core mass falls this far below the union's, the union is sharper at its
// centre than a band can be (sharp lobes with rough ones: the fingerprinted tray, 30–40 % short) and
// gets an atom. Lower reaches polished granite's unions of spread cores with mica flecks and brightens
// its highlight; higher leaves the tray much of its loss. Chosen by a sweep on the tray and polished
// granite (docs/mip-algorithm.md, §9).
constexpr double kAtomCoreShortfall = 0.1;

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

}  // namespace

double UnionMass::operator()(double R2) const {
  const double R = std::sqrt(R2);
  double mass = 0;
  for (const Member& x : members) {
    const Summary& a = *x.sum;
    const double t = tan2_between(a.n, n);
    if (std::isfinite(t)) mass += (by_amp ? a.amp : a.weight) * cone_mass_at(a.d_shape, std::sqrt(t), R);
  }
  return mass / K;
}

double UnionMass::bound(double R2) const {
  double mass = 0;
  for (const Member& x : members) mass += (by_amp ? x.sum->amp : x.sum->weight) * centred_cone_mass(x.sum->d_shape, R2);
  return mass / K;
}

// Why the atom: a band's mass within the core (slope radius 1/√P) is fixed by q = AP alone, and a union
// of sharp lobes with rough ones — polished metal with fingerprints, clean at one texel and oily at the
// next — has far more there: a band with its A and P spreads the sharp lobes' peak over the decades
// between (−30 % of the tray's highlight over ±1° of views at some level-4 texels; −5.4 % over the whole
// tray by level 8). The atom's share is fitted to the union's core mass, and the upper part is a band
// or a second atom, whichever then keeps the union's mass in the LOD camera's cone (kSkirtTan2) better:
// a band for a sharp cluster over a spread of rough lobes, an atom for two clusters
// (docs/mip-algorithm.md, §4.1).
void set_shape(Lobe& m, double A, double P, const UnionMass* union_mass) {
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
    if (!(band_core < union_mass->bound(1 / P) * (1 - kAtomCoreShortfall))) return;
    const double core = (*union_mass)(1 / P);
    if (!(band_core < core * (1 - kAtomCoreShortfall))) return;
    const MixtureFit a = fit_atom_band(q, 2 * span.u, core, P), b = fit_two_point(q, core, P);
    const double cam = (*union_mass)(kSkirtTan2), s = kSkirtTan2 * P;
    // (Taking the band whenever it is within 1 % of the cone, to save the second fit, raised polished
    // granite's highlight at level 7 from +1.6 % to +3.3 %: the better of the two compounds.)
    const MixtureFit& f = std::abs(a.mass(s) - cam) <= std::abs(b.mass(s) - cam) ? a : b;
    // The upper end at least 0.2 % above the atom: what the MIP file stores as a mixture (0.1 %,
    // stored_lobe.h) once α is rounded to a half (5e-4 on α²).
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

}  // namespace svbrdf::reduction
