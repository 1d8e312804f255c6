#pragma once
// A lobe's mean normal as the MIP file stores it, in 6 bytes where three floats took 12:
//   direction  the unit direction, octahedral (Cigolle et al. 2014, "A Survey of Efficient
//              Representations for Independent Unit Vectors", JCGT 3(2)), warped toward the pole: two
//              16-bit signed codes q in one 32-bit word, low half x; c = q/32767 ∈ [−1, 1] and the
//              octahedral coordinate is p = c·(1/16 + (15/16)·|c|). The code is the one nearest to the
//              direction among the four around it ("precise" encoding).
//   deficit    1 − |normal| (the normals' spread, lobe.h) as a half float, first rounded to a multiple
//              of 2^-20 so that encoding a decoded normal gives back the same code: float rounding in
//              |normal| (≈ 1e-7) stays below half that step.
// Why the warp: a coarse level's normals gather near the pole, and there a code step matters to the
// sharpest lobes. The linear code (the octahedral coordinate c itself) has a step of 3.05e-5 rad
// everywhere. Near the peak of a lobe of α ≈ 0.005 (polished metal), a shift of δ changes
// D by about 4δθ/(α² + θ²): 1 % at θ = 0.2° per step. Texels that share a normal (a flat polish, a
// height field's repeated slopes) round the same way, so those errors add up instead of averaging
// out: the polished tray's whole-texture highlight was off by 0.45 % at level 1, a first azimuthal
// harmonic (a shift), where the exact union has none. The warp's step is 1/16 of that at the pole
// (1.9e-6 rad), about 1/4 at 1° of tilt, and 1.9× it at the square's edges (normals on the horizon):
// at most 8.4e-5 rad off anywhere (tested), 1.2e-5 within 1° of the pole (tested). It is no
// finer at the pole because a normal along the fold (the lower hemisphere's edge) must still decode to
// a float direction that encodes to the same code.
// store(load(s)) == s for every stored s (tested), which is what keeps the file's round trip
// bit-identical: the BRDF pyramid holds its normals as decode(encode(n)) (round_to_stored).
#include <cstdint>

#include <glm/vec3.hpp>

namespace svbrdf {

struct StoredNormal {
  std::uint32_t direction = 0;  // octahedral code
  float deficit = 0.0f;         // 1 − length, a value a half float holds exactly
};

StoredNormal store_normal(const glm::vec3& normal);
glm::vec3 load_normal(const StoredNormal& stored);
inline glm::vec3 round_normal(const glm::vec3& normal) { return load_normal(store_normal(normal)); }

}  // namespace svbrdf
