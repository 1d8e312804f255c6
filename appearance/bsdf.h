#pragma once
// The scattering interface of CGPP §27.14 in the project's words. Directions are in the local
// shading frame (z = normal), both pointing away from the surface: wi toward the light, wo toward
// the viewer. A BSDF has a finite part (eval, pdf, finite samples) and impulses (delta lobes).
#include <array>
#include <glm/glm.hpp>

namespace svbrdf {

using Rgb = glm::vec3;

// One delta lobe: radiance arriving from `direction` leaves toward the query direction scaled by
// `magnitude` (already including the cosine/delta bookkeeping, as in §27.14).
struct Impulse {
  glm::vec3 direction{0, 0, 1};
  Rgb magnitude{0};
};

// At most two impulses per query: a dielectric's reflection and refraction.
struct Impulses {
  std::array<Impulse, 2> items{};
  int count = 0;
  void add(const glm::vec3& d, const Rgb& m) { items[static_cast<std::size_t>(count++)] = {d, m}; }
};

enum class SampleKind { finite, impulse, absorbed };

// The result of sample(wo, u): wi drawn with density `pdf` (finite; solid-angle measure), or an
// impulse chosen with probability `pdf` (a discrete probability then), or absorbed.
// `weight` = f·|wi.z| / pdf for finite samples, magnitude / probability for impulses, 0 when absorbed.
struct BsdfSample {
  glm::vec3 wi{0, 0, 1};
  float pdf = 0;
  Rgb weight{0};
  SampleKind kind = SampleKind::absorbed;
};

// Uniform random numbers for one sample: u.x selects among lobes / the energy split,
// u.y and u.z drive the direction.
//
// The energy split (§27.14): the models of this library scatter (return an impulse or a finite
// sample) exactly when u.x < scatter_probability(wo) and are absorbed otherwise; inside that
// interval they use u.x / scatter_probability(wo) for their own choices. A mixture can thus hand
// each lobe its own slice of u.x and keep every lobe's absolute split (mixture.h). A finite
// direction that lands below the horizon is reported as absorbed too.
using SampleU = glm::vec3;

class Bsdf {
 public:
  virtual ~Bsdf() = default;
  // The finite part f(wi, wo).
  virtual Rgb eval(const glm::vec3& wi, const glm::vec3& wo) const = 0;
  // Directions from which light reaches wo through an impulse.
  virtual Impulses impulses_in(const glm::vec3& /*wo*/) const { return {}; }
  // Directions toward which light arriving along wi leaves through an impulse.
  virtual Impulses impulses_out(const glm::vec3& /*wi*/) const { return {}; }
  virtual BsdfSample sample(const glm::vec3& wo, const SampleU& u) const = 0;
  // The density (solid angle) with which sample() produces finite wi, including the probability of
  // choosing the finite part.
  virtual float pdf(const glm::vec3& wi, const glm::vec3& wo) const = 0;
  // The probability that sample(wo, ·) does not choose "absorbed" by its energy split (before the
  // below-horizon rule), in [0, 1]. A model that never absorbs by choice keeps this default.
  virtual float scatter_probability(const glm::vec3& /*wo*/) const { return 1.0f; }
};

}  // namespace svbrdf
