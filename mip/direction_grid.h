#pragma once
// The direction set of the error metric (../shared/spec/brdf-mip.md, "The error metric"):
// θ ∈ {0°, 10°, ..., 80°} × φ ∈ {0°, 45°, ..., 315°}, θ = 0 once — 65 directions in the geometric
// tangent frame — and all 65 × 65 = 4225 (wi, wo) pairs. A BRDF "table" holds F for every pair,
// pair p = i·65 + o for wi = direction i and wo = direction o.
#include <array>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "mip/lobe.h"

namespace svbrdf {

class DirectionGrid {
 public:
  static constexpr int kDirections = 65;
  static constexpr int kPairs = kDirections * kDirections;

  // The one grid (immutable after construction, shared by every thread).
  static const DirectionGrid& get();

  const glm::dvec3& direction(int d) const { return dirs_[static_cast<std::size_t>(d)]; }
  static int wi_index(int pair) { return pair / kDirections; }
  static int wo_index(int pair) { return pair % kDirections; }
  const PairTerms<double>& pair_d(int pair) const { return pairs_d_[static_cast<std::size_t>(pair)]; }
  const PairTerms<float>& pair_f(int pair) const { return pairs_f_[static_cast<std::size_t>(pair)]; }

  // The same pairs as structures of arrays (h.x, h.y, h.z, w), for loops the compiler vectorizes.
  template <class T>
  struct Columns {
    std::vector<T> hx, hy, hz, w;
  };
  const Columns<double>& columns_d() const { return cols_d_; }
  const Columns<float>& columns_f() const { return cols_f_; }

 private:
  DirectionGrid();
  std::array<glm::dvec3, kDirections> dirs_{};
  std::vector<PairTerms<double>> pairs_d_;
  std::vector<PairTerms<float>> pairs_f_;
  Columns<double> cols_d_;
  Columns<float> cols_f_;
};

// A table of F over the 4225 pairs, accumulated in double.
using BrdfTable = std::vector<glm::dvec3>;
inline BrdfTable make_table() { return BrdfTable(DirectionGrid::kPairs, glm::dvec3(0)); }

// table += scale · (lobe's weighted f_eff) for every pair, the lobe evaluated in double precision
// (the exact reference) or in float (what the renderer evaluates), accumulated in double.
void accumulate_lobe_double(const Lobe& lobe, double scale, std::span<glm::dvec3> table);
// spec_scale: null, or per pair a factor on the specular term (a coarse texel's radial correction).
void accumulate_lobe_float(const Lobe& lobe, double scale, std::span<glm::dvec3> table, const float* spec_scale = nullptr);

}  // namespace svbrdf
