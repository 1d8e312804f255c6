#include "chi2.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "appearance/rng.h"

namespace svbrdf::testing {
namespace {

constexpr int kFaces = 6, kTop = 8;  // top grid: kTop × kTop cells on each cube face
constexpr int kTopCells = kFaces * kTop * kTop;

// 4-point Gauss–Legendre nodes and weights on [−1, 1].
constexpr double kGlX[4] = {-0.8611363115940526, -0.3399810435848563, 0.3399810435848563, 0.8611363115940526};
constexpr double kGlW[4] = {0.3478548451374538, 0.6521451548625461, 0.6521451548625461, 0.3478548451374538};

// A rectangle [u0, u1) × [v0, v1) on one face of the cube [−1, 1]³. Face f: axis f / 2, sign + for
// even f. On face ±x, (u, v) = (w.y, w.z)/|w.x|; ±y: (w.x, w.z)/|w.y|; ±z: (w.x, w.y)/|w.z|; so
// v = 0 is the horizon on the four side faces: the horizon is a grid line.
struct Cell {
  int face;
  double u0, u1, v0, v1;
};

// A sample's coordinates: (face, u, v).
using Coords = glm::dvec3;

glm::vec3 direction(int face, double u, double v) {
  const double s = face % 2 == 0 ? 1.0 : -1.0;
  glm::dvec3 d;
  switch (face / 2) {
    case 0: d = {s, u, v}; break;
    case 1: d = {u, s, v}; break;
    default: d = {u, v, s}; break;
  }
  return glm::vec3(glm::normalize(d));
}

// dω = du dv / (1 + u² + v²)^{3/2} on a cube face.
double jacobian(double u, double v) {
  const double q = 1.0 + u * u + v * v;
  return 1.0 / (q * std::sqrt(q));
}

Coords coords(const glm::vec3& wf) {
  const glm::dvec3 w(wf), a = glm::abs(w);
  int axis = 2;
  if (a.x >= a.y && a.x >= a.z) axis = 0;
  else if (a.y >= a.z) axis = 1;
  const int face = 2 * axis + (w[axis] < 0 ? 1 : 0);
  const double m = a[axis];
  double u, v;
  switch (axis) {
    case 0: u = w.y / m; v = w.z / m; break;
    case 1: u = w.x / m; v = w.z / m; break;
    default: u = w.x / m; v = w.y / m; break;
  }
  const double top = std::nextafter(1.0, 0.0);
  return {face, std::clamp(u, -1.0, top), std::clamp(v, -1.0, top)};
}

int top_index(const Coords& s) {
  const int iu = std::min(kTop - 1, static_cast<int>((s.y + 1.0) * 0.5 * kTop));
  const int iv = std::min(kTop - 1, static_cast<int>((s.z + 1.0) * 0.5 * kTop));
  return (static_cast<int>(s.x) * kTop + iu) * kTop + iv;
}

bool contains(const Cell& c, const Coords& s) {
  return static_cast<int>(s.x) == c.face && s.y >= c.u0 && s.y < c.u1 && s.z >= c.v0 && s.z < c.v1;
}

double integrate(const Bsdf& bsdf, const glm::vec3& wo, const Cell& c) {
  const double hu = 0.5 * (c.u1 - c.u0), hv = 0.5 * (c.v1 - c.v0);
  const double mu = 0.5 * (c.u1 + c.u0), mv = 0.5 * (c.v1 + c.v0);
  double sum = 0;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) {
      const double u = mu + hu * kGlX[i], v = mv + hv * kGlX[j];
      sum += kGlW[i] * kGlW[j] * jacobian(u, v) * static_cast<double>(bsdf.pdf(direction(c.face, u, v), wo));
    }
  return sum * hu * hv;
}

struct Builder {
  const Bsdf& bsdf;
  glm::vec3 wo;
  const Chi2Options& opt;
  const std::vector<Coords>& pilot;
  double pilot_scale;  // N / pilot size
  std::vector<Cell> leaves;
  std::vector<double> mass;

  void build(const Cell& c, double coarse, int depth, const std::vector<int>& inside) {
    const double mu = 0.5 * (c.u0 + c.u1), mv = 0.5 * (c.v0 + c.v1);
    const Cell kids[4] = {{c.face, c.u0, mu, c.v0, mv}, {c.face, c.u0, mu, mv, c.v1}, {c.face, mu, c.u1, c.v0, mv},
                          {c.face, mu, c.u1, mv, c.v1}};
    double fine[4], total = 0;
    for (int k = 0; k < 4; ++k) total += fine[k] = integrate(bsdf, wo, kids[k]);
    const double n = opt.samples, k = static_cast<double>(inside.size());
    const bool busy = k * pilot_scale > opt.split_expected;
    const bool heavy = total * n > opt.split_expected;
    const bool inexact = std::abs(total - coarse) * n > 0.02 + 2e-3 * total * n;
    // The pilot disagrees with the quadrature (by more than 4 Poisson deviations, or it found
    // samples where the quadrature sees none): a feature of the density (an edge, a narrow peak)
    // that the quadrature nodes straddle or miss.
    const double pilot_expected = total * n / pilot_scale;
    const bool missed =
        std::abs(k - pilot_expected) > 4 * std::sqrt(pilot_expected + 1) + 2 || (k > 0 && pilot_expected < 0.05 * k);
    if (depth < opt.max_depth && (busy || heavy || inexact || missed)) {
      for (int q = 0; q < 4; ++q) {
        std::vector<int> sub;
        for (int i : inside)
          if (contains(kids[q], pilot[static_cast<std::size_t>(i)])) sub.push_back(i);
        build(kids[q], fine[q], depth + 1, sub);
      }
      return;
    }
    leaves.push_back(c);
    mass.push_back(total);
  }
};

// Regularized lower incomplete gamma P(a, x) by its series, upper Q(a, x) by the continued
// fraction (modified Lentz), each where it converges fast (Abramowitz & Stegun 6.5.29, 6.5.31).
double gamma_q(double a, double x) {
  if (x <= 0) return 1.0;
  const double log_prefix = a * std::log(x) - x - std::lgamma(a);
  if (x < a + 1) {
    double term = 1.0 / a, sum = term;
    for (int n = 1; n < 10000; ++n) {
      term *= x / (a + n);
      sum += term;
      if (term < sum * 1e-16) break;
    }
    return std::max(0.0, 1.0 - sum * std::exp(log_prefix));
  }
  const double tiny = 1e-300;
  double b = x + 1 - a, c = 1 / tiny, d = 1 / b, h = d;
  for (int i = 1; i < 10000; ++i) {
    const double an = -i * (i - a);
    b += 2;
    d = an * d + b;
    if (std::abs(d) < tiny) d = tiny;
    c = b + an / c;
    if (std::abs(c) < tiny) c = tiny;
    d = 1 / d;
    const double delta = d * c;
    h *= delta;
    if (std::abs(delta - 1) < 1e-16) break;
  }
  return std::exp(log_prefix) * h;
}

}  // namespace

double chi2_survival(double x, int dof) { return gamma_q(0.5 * dof, 0.5 * x); }

Chi2Result chi2_test(const Bsdf& bsdf, const glm::vec3& wo, const Chi2Options& opt) {
  auto draw = [&](std::uint64_t seed, int n, std::vector<Coords>& finite) {
    Rng rng(mix64(seed), 0xc41);
    for (int i = 0; i < n; ++i) {
      const SampleU u(rng.next_float(), rng.next_float(), rng.next_float());
      const BsdfSample s = bsdf.sample(wo, u);
      if (s.kind == SampleKind::finite) finite.push_back(coords(s.wi));
    }
  };
  std::vector<Coords> pilot, main;
  const int pilot_n = std::max(1000, opt.samples / 4);
  draw(opt.seed ^ 0x9e3779b97f4a7c15ULL, pilot_n, pilot);
  draw(opt.seed, opt.samples, main);

  Builder b{bsdf, wo, opt, pilot, static_cast<double>(opt.samples) / pilot_n, {}, {}};
  const double step = 2.0 / kTop;
  std::vector<std::vector<int>> top(kTopCells);
  for (std::size_t i = 0; i < pilot.size(); ++i)
    top[static_cast<std::size_t>(top_index(pilot[i]))].push_back(static_cast<int>(i));
  // Leaves of a top cell are contiguous: first[t] .. first[t + 1].
  std::vector<std::size_t> first(kTopCells + 1, 0);
  for (int f = 0; f < kFaces; ++f)
    for (int iu = 0; iu < kTop; ++iu)
      for (int iv = 0; iv < kTop; ++iv) {
        const auto t = static_cast<std::size_t>((f * kTop + iu) * kTop + iv);
        first[t] = b.leaves.size();
        const Cell c{f, -1.0 + iu * step, -1.0 + (iu + 1) * step, -1.0 + iv * step, -1.0 + (iv + 1) * step};
        b.build(c, integrate(bsdf, wo, c), 0, top[t]);
      }
  const std::size_t nleaves = b.leaves.size();
  first[kTopCells] = nleaves;
  std::vector<double> observed(nleaves + 1, 0.0);
  for (const Coords& s : main) {
    const auto t = static_cast<std::size_t>(top_index(s));
    for (std::size_t li = first[t]; li < first[t + 1]; ++li)
      if (contains(b.leaves[li], s)) {
        observed[li] += 1;
        break;
      }
  }

  const double n = opt.samples;
  double integral = 0;
  for (double m : b.mass) integral += m;
  std::vector<double> expected(b.mass.begin(), b.mass.end());
  for (double& e : expected) e *= n;
  observed[nleaves] = n - static_cast<double>(main.size());  // impulses and absorbed
  expected.push_back(n * (1.0 - integral));

  // Pool consecutive bins up to min_expected; a short tail joins the last pool.
  std::vector<double> po, pe;
  std::vector<std::size_t> pool_first;  // first leaf of each pool, for the failure message
  double o = 0, e = 0;
  std::size_t start = 0;
  for (std::size_t i = 0; i < expected.size(); ++i) {
    o += observed[i];
    e += expected[i];
    if (e >= opt.min_expected) {
      po.push_back(o);
      pe.push_back(e);
      pool_first.push_back(start);
      start = i + 1;
      o = e = 0;
    }
  }
  if ((o > 0 || e > 0) && !pe.empty()) {
    po.back() += o;
    pe.back() += e;
  } else if (pe.empty()) {
    po.push_back(o);
    pe.push_back(e);
    pool_first.push_back(0);
  }
  Chi2Result r;
  r.leaves = static_cast<int>(nleaves);
  r.bins = static_cast<int>(pe.size());
  r.pdf_integral = integral;
  r.finite_fraction = static_cast<double>(main.size()) / n;
  double worst = -1;
  for (std::size_t i = 0; i < pe.size(); ++i) {
    const double term = pe[i] > 0 ? (po[i] - pe[i]) * (po[i] - pe[i]) / pe[i] : (po[i] > 0 ? 1e30 : 0.0);
    r.statistic += term;
    if (term > worst) {
      worst = term;
      char buf[200];
      const std::size_t l = pool_first[i];
      if (l < nleaves)
        std::snprintf(buf, sizeof buf, "pooled bin %zu of %zu from face %d (u %.5f, v %.5f): observed %.0f, expected %.2f",
                      i, pe.size(), b.leaves[l].face, b.leaves[l].u0, b.leaves[l].v0, po[i], pe[i]);
      else
        std::snprintf(buf, sizeof buf, "the non-finite bin: observed %.0f, expected %.2f", po[i], pe[i]);
      r.worst = buf;
    }
  }
  r.dof = std::max(1, r.bins - 1);
  r.p_value = chi2_survival(r.statistic, r.dof);
  return r;
}

}  // namespace svbrdf::testing
