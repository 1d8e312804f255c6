#include "mip/direction_grid.h"

#include <cmath>

#include "appearance/microfacet_core.h"
#include "base/math.h"

namespace svbrdf {

DirectionGrid::DirectionGrid() {
  dirs_[0] = glm::dvec3(0, 0, 1);
  int d = 1;
  for (int t = 1; t <= 8; ++t)
    for (int k = 0; k < 8; ++k) {
      const double theta = radians_of(10.0 * t), phi = radians_of(45.0 * k);
      dirs_[static_cast<std::size_t>(d++)] =
          glm::dvec3(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta));
    }
  pairs_d_.resize(kPairs);
  pairs_f_.resize(kPairs);
  for (int p = 0; p < kPairs; ++p) {
    const glm::dvec3 wi = dirs_[static_cast<std::size_t>(wi_index(p))];
    const glm::dvec3 wo = dirs_[static_cast<std::size_t>(wo_index(p))];
    pairs_d_[static_cast<std::size_t>(p)] = pair_terms<double>(wi, wo);
    pairs_f_[static_cast<std::size_t>(p)] = pair_terms<float>(glm::vec3(wi), glm::vec3(wo));
  }
  auto fill = [&](auto& cols, const auto& pairs) {
    for (const auto& pt : pairs) {
      cols.hx.push_back(pt.h.x), cols.hy.push_back(pt.h.y), cols.hz.push_back(pt.h.z);
      cols.w.push_back(pt.fresnel_w);
    }
  };
  fill(cols_d_, pairs_d_);
  fill(cols_f_, pairs_f_);
}

const DirectionGrid& DirectionGrid::get() {
  static const DirectionGrid grid;
  return grid;
}

namespace {

// lobe_eval over every pair, with everything that depends on one direction only hoisted out of the
// pair loop: the sides, and the visibility's root √(α² + (1 − α²)·cos²) per direction (smith_ggx_root;
// the pair loop then forms smith_ggx_visibility from two of them). The same formulas as lobe.h term by
// term (the tests hold the two to rounding).
template <class T>
void accumulate(const Lobe& lobe, double scale, std::span<glm::dvec3> table, const float* spec_scale) {
  using V3 = glm::vec<3, T>;
  const DirectionGrid& grid = DirectionGrid::get();
  const LobeShape<T> shape = lobe_shape<T>(lobe);
  if (!shape.valid) return;
  constexpr int nd = DirectionGrid::kDirections;
  if (shape.alpha2_hi > 0 || shape.ggx != T(1) || shape.stretched) {
    // Mixture shapes (lobe.h): V depends on the pair through the mixture's α², so nothing hoists;
    // nor through a stretch (V's roots depend on each direction's azimuth to it, D's on the pair's).
    for (int pr = 0; pr < DirectionGrid::kPairs; ++pr) {
      const PairTerms<T>* pt;
      if constexpr (std::is_same_v<T, double>)
        pt = &grid.pair_d(pr);
      else
        pt = &grid.pair_f(pr);
      const T k = spec_scale ? T(spec_scale[pr]) : T(1);
      table[static_cast<std::size_t>(pr)] += scale * glm::dvec3(lobe_eval(lobe, shape, *pt, k));
    }
    return;
  }
  const T a2 = shape.alpha2;
  std::array<T, nd> wi_factor{}, wo_factor{}, cosine{}, root{};
  for (int d = 0; d < nd; ++d) {
    const V3 w(grid.direction(d));
    const T c = glm::dot(shape.n, w);
    const LobeSide<T> si = lobe_wi_side(shape, c), so = lobe_wo_side(shape, c);
    const auto k = static_cast<std::size_t>(d);
    wi_factor[k] = si.factor * T(lobe.weight) / w.z;
    wo_factor[k] = so.factor;
    cosine[k] = si.c;  // the clamped cosine (the same for both sides)
    root[k] = smith_ggx_root(a2, si.c);
  }
  constexpr T kInvPi = kInvPiOf<T>;
  // Plain GGX here (the shaped lobes took the loop above).
  const T nx = shape.n.x, ny = shape.n.y, nz = shape.n.z;
  const T rho_r = T(0.96) * kInvPi * T(lobe.diffuse.r), rho_g = T(0.96) * kInvPi * T(lobe.diffuse.g),
          rho_b = T(0.96) * kInvPi * T(lobe.diffuse.b);
  const T f0r = lobe.f0.r, f0g = lobe.f0.g, f0b = lobe.f0.b, f90 = lobe.f90;
  const T d90_r = kInvPi * T(lobe.diffuse90.r), d90_g = kInvPi * T(lobe.diffuse90.g), d90_b = kInvPi * T(lobe.diffuse90.b);
  const DirectionGrid::Columns<T>* cols;
  if constexpr (std::is_same_v<T, double>)
    cols = &grid.columns_d();
  else
    cols = &grid.columns_f();
  std::array<T, nd> out_r{}, out_g{}, out_b{};
  for (int i = 0; i < nd; ++i) {
    const auto ki = static_cast<std::size_t>(i);
    if (!(wi_factor[ki] > 0)) continue;
    const T ci = cosine[ki], gi = root[ki], fi = wi_factor[ki];
    const T* hx = cols->hx.data() + i * nd;
    const T* hy = cols->hy.data() + i * nd;
    const T* hz = cols->hz.data() + i * nd;
    const T* fw = cols->w.data() + i * nd;
    static const std::array<float, DirectionGrid::kPairs> kOnes = [] {
      std::array<float, DirectionGrid::kPairs> a{};
      a.fill(1.0f);
      return a;
    }();
    const float* ks = (spec_scale ? spec_scale : kOnes.data()) + i * nd;
    // Branch-free over wo, so it vectorizes; a wo with factor 0 contributes 0 (its cosine is
    // clamped positive, so nothing divides by 0).
    for (int o = 0; o < nd; ++o) {
      const T ch = nx * hx[o] + ny * hy[o] + nz * hz[o];
      const T cx = ny * hz[o] - nz * hy[o], cy = nz * hx[o] - nx * hz[o], cz = nx * hy[o] - ny * hx[o];
      // D's denominator |n×h|² + (n·h)²·α² > 0 for α² ≥ 1e-6, so its division is always safe to execute.
      const T d = (ch > 0 ? T(1) : T(0)) * ggx_d_terms(a2, cx * cx + cy * cy + cz * cz, ch * ch);
      // smith_ggx_visibility(α², ci, co) from the hoisted roots.
      const T vis = T(0.5) / (cosine[static_cast<std::size_t>(o)] * gi + ci * root[static_cast<std::size_t>(o)]);
      const T w = fw[o], s = vis * d * T(ks[o]), k = fi * wo_factor[static_cast<std::size_t>(o)];
      out_r[static_cast<std::size_t>(o)] = k * ((T(1) - w) * rho_r + w * d90_r + s * (f0r + (f90 - f0r) * w));
      out_g[static_cast<std::size_t>(o)] = k * ((T(1) - w) * rho_g + w * d90_g + s * (f0g + (f90 - f0g) * w));
      out_b[static_cast<std::size_t>(o)] = k * ((T(1) - w) * rho_b + w * d90_b + s * (f0b + (f90 - f0b) * w));
    }
    glm::dvec3* row = table.data() + i * nd;
    for (int o = 0; o < nd; ++o) {
      const auto ko = static_cast<std::size_t>(o);
      row[o] += scale * glm::dvec3(out_r[ko], out_g[ko], out_b[ko]);
    }
  }
}

}  // namespace

void accumulate_lobe_double(const Lobe& lobe, double scale, std::span<glm::dvec3> table) {
  accumulate<double>(lobe, scale, table, nullptr);
}
void accumulate_lobe_float(const Lobe& lobe, double scale, std::span<glm::dvec3> table, const float* spec_scale) {
  accumulate<float>(lobe, scale, table, spec_scale);
}

}  // namespace svbrdf
