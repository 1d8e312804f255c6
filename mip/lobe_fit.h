#pragma once
// Private to mip/: included by mip's .cpp files only (lobe_reduction.h is the reduction's public face).
// The shape of a merged lobe (lobe.h) from two moments of its union — the tail coefficient A and the
// peak P — and, where one shape of that A and P would lose the union's centre, from its mass within a
// cone about the merged normal (set_shape; docs/mip-algorithm.md, §4.1 and §4.3).
#include <span>

#include <glm/glm.hpp>

#include "mip/lobe.h"
#include "mip/merge_cost.h"

namespace svbrdf::reduction {

// A union's mass of D within slope radius² R² of the merged normal n, per unit of K (its amplitudes,
// or its weights when no lobe has a specular part: !by_amp), as A and P are: exactly (each member's
// disc mass, tilted by its angle to n), and bounded from above at no quadrature (each member as if
// centred on n).
struct UnionMass {
  std::span<const Member> members;
  glm::dvec3 n;
  bool by_amp;
  double K;
  double operator()(double R2) const;
  double bound(double R2) const;
};

// The lobe shape with tail coefficient A and peak P (lobe.h), set on m (its alpha2, alpha2_hi, ggx and
// skirt): when AP ≥ 1 a roughness mixture, the log-uniform band on [g/e^u, g·e^u] (g = √(A/P),
// sinh(u)/u = √(AP)) unless the union is sharper at its centre than that band, else one core of
// α² = 1/P whose GGX share μ = AP thins the tail (the rest Beckmann), with a skirt where it is narrow.
// Without union_mass, the band or the core alone.
void set_shape(Lobe& m, double A, double P, const UnionMass* union_mass);

}  // namespace svbrdf::reduction
