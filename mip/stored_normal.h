#pragma once
// A lobe's mean normal as the MIP file stores it (version 6), in 6 bytes where three floats took 12:
//   direction  the unit direction, octahedral (Cigolle et al. 2014, "A Survey of Efficient
//              Representations for Independent Unit Vectors", JCGT 3(2)): two 16-bit signed
//              coordinates in one 32-bit word, low half x; the code nearest to the direction among
//              the four around it ("precise" encoding) — at most 3e-5 rad off (tested), 3 % of the
//              sharpest lobe's α = 1e-3.
//   deficit    1 − |normal| (the normals' spread, lobe.h) as a half float, first rounded to a multiple
//              of 2^-20 so that encoding a decoded normal gives back the same code: float rounding in
//              |normal| (≈ 1e-7) stays below half that step.
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
