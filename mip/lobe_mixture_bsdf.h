#pragma once
// A texel's mixture of lobes (lobe.h) as a Bsdf the integrator can evaluate and sample: what the MIP
// lookups fill (mip.h). Directions are in the geometric tangent frame (z = the surface's
// interpolated normal, before any normal map): the lobes carry their own normals.
//
// A value type: it copies the texel's lobes (at most kMaxLobes) and their shapes in, so it allocates
// nothing, outlives the lookup freely and is safe to use from any thread.
//
// Sampling (a "weak" sampler in the sense of brdf-models.md, exact through its weights): with
// probability kDefensive a cosine-weighted direction about the geometric normal, which covers every
// direction where f may be non-zero (including where a spread lobe reflects past its mean horizon);
// otherwise a lobe chosen in proportion to an estimate of its albedo, then its diffuse part
// (cosine-weighted about the lobe's normal) or its specular part (GGX visible normals about the
// lobe's normal, Heitz 2018 via appearance/microfacet_distribution.h, at the lobe's α², or half at
// each end of a roughness mixture's range) in proportion to theirs. pdf()
// is the density of that whole mixture; weight = f·wi.z/pdf with the whole f.
//
// A coated texel (KHR_materials_clearcoat, coat_layer.h) also carries its coat lobes: eval is the
// layered f_eff of coat_layer.h (the base lobes attenuated by 1 − coat_k·F̄(wo), the coat lobes under the
// base's cosine factor K), exactly as texel_eval evaluates the texel; the sampler chooses among the base
// and the coat lobes alike, a coat lobe by its specular part alone (F0 0.04, F90 1, no diffuse term).
//
// A texel whose lobes transmit (a thin-walled KHR_materials_transmission, lobe.h "Transmission") is
// non-zero for wi below the surface: each lobe's BTDF under its sheen's scaling and the coat's
// attenuation. The sampler chooses a lobe's transmission in proportion to its estimate mean(τ), draws
// the lobe's visible normals and mirrors the reflected direction through the lobe's plane (an isometry:
// the density is the reflection's at the mirrored direction); the defensive share goes below the
// surface in proportion to the transmission's share of the estimates. A diffuse transmission
// (KHR_materials_diffuse_transmission, diffuse_transmission.h) is evaluated beside it, under the same
// layers, and sampled as the lobe's diffuse part mirrored through the lobe's plane (cosine-weighted
// about −n̂), chosen in proportion to its estimate mean(τd).
//
// A texel with a sheen (KHR_materials_sheen, sheen_layer.h: set_sheen) scales each base lobe by its
// albedo scaling and adds the sheen about the base lobes' normals, under the coat where there is one;
// the sampler draws the sheen uniformly over the hemisphere (appearance/sheen.h sample_sheen) with a
// probability in proportion to its albedo estimate mean(C̄)·E(wo.z).
#include <array>
#include <span>

#include "appearance/bsdf.h"
#include "appearance/frame.h"
#include "mip/lobe.h"
#include "mip/lobe_reduction.h"
#include "mip/radial_correction.h"
#include "textures/material_texels.h"

namespace svbrdf {

class LobeMixtureBsdf final : public Bsdf {
 public:
  static constexpr float kDefensive = 0.1f;

  LobeMixtureBsdf() = default;
  // Copies the first kMaxLobes lobes (and coat lobes).
  explicit LobeMixtureBsdf(std::span<const Lobe> lobes, std::span<const Lobe> coat = {}) { assign(lobes, coat); }
  // Becomes the mixture of `lobes` (the first kMaxLobes) under the coat lobes `coat` (the first kMaxLobes;
  // none: no coat), in place: a path reuses one object for every hit rather than constructing (and, in
  // std::optional, zero-filling) it per bounce.
  void assign(std::span<const Lobe> lobes, std::span<const Lobe> coat = {});

  // The texel's radial correction (radial_correction.h): eval multiplies every lobe's specular term by
  // R(θh). Null: none. assign() clears it; both pointers must outlive the object's use.
  void set_correction(const RadialCorrection* correction, const RadialGrid* grid) {
    correction_ = correction;
    grid_ = grid;
    own_correction_ = false;
  }
  // The same from a correction the object keeps a copy of (a texel decoded from a record, mip.h, whose
  // memory ends with the lookup).
  void set_correction_copy(const RadialCorrection& correction, const RadialGrid* grid) {
    correction_copy_ = correction;
    correction_ = nullptr;
    grid_ = grid;
    own_correction_ = true;
  }
  // The texel's sheen means (sheen_layer.h), over the base lobes assign() took with their sheen shares;
  // colour 0 or no lobe with a share: none. assign() clears it.
  void set_sheen(const SheenLayer& sheen);
  bool has_sheen() const { return sheen_on_; }
  // Whether some base lobe transmits (lobe.h, "Transmission", or diffusely, diffuse_transmission.h): eval
  // is then non-zero below the surface.
  bool has_transmission() const { return transmits_; }

  int size() const { return count_; }
  const Lobe& lobe(int k) const { return slot(k).lobe; }
  // The coat lobes (coat_layer.h), after the base lobes in the slots.
  int coat_size() const { return coat_count_; }
  const Lobe& coat_lobe(int k) const { return slot(count_ + k).lobe; }
  // The weighted sum of the lobes' normals, unnormalized (zero when there is no lobe): the shading
  // normal the mixture stands for, once normalized (the normal AOV).
  glm::vec3 mean_normal() const {
    glm::vec3 n(0.0f);
    for (int k = 0; k < count_; ++k) n += slot(k).lobe.weight * slot(k).lobe.normal;
    return n;
  }

  Rgb eval(const glm::vec3& wi, const glm::vec3& wo) const override;
  BsdfSample sample(const glm::vec3& wo, const SampleU& u) const override;
  float pdf(const glm::vec3& wi, const glm::vec3& wo) const override;

 private:
  // Base lobes, then coat lobes.
  static constexpr int kSlots = 2 * kMaxLobes;
  struct Choice {
    std::array<float, kSlots> lobe{};     // probability of lobe k (sums to 1 − kDefensive)
    std::array<float, kSlots> diffuse{};  // within lobe k, probability of its diffuse part
    std::array<float, kSlots> transmit{};  // within lobe k, probability of its transmission
    std::array<float, kSlots> dtrans{};    // within lobe k, probability of its diffuse transmission
    float sheen = 0;                      // probability of the sheen's uniform sampler
    float below = 0;                      // within the defensive share, probability below the surface
  };
  Choice choice(const glm::vec3& wo) const;
  float pdf_with(const Choice& c, const glm::vec3& wi, const glm::vec3& wo) const;
  // eval and pdf_with for wi below the surface (wo above): the transmission.
  Rgb transmission_eval(const glm::vec3& wi, const glm::vec3& wo) const;
  float transmission_pdf(const Choice& c, const glm::vec3& wi, const glm::vec3& wo) const;
  // The density of a lobe's specular sampler for the reflection of wo about the unit half vector h
  // (wo·h > 0).
  static float specular_pdf(const LobeShape<float>& sh, const glm::vec3& wo, const glm::vec3& h);

  // A lobe with what eval and the sampling choice need of it, computed once per hit.
  struct Slot {
    Lobe lobe;
    LobeShape<float> shape;
    float diffuse_albedo, spec_albedo, trans_albedo, dtrans_albedo;
  };
  // Slots past count_ + coat_count_ stay uninitialized: a hit fills one to four of them, and
  // value-initializing all of them (~0.7 KB per hit for eight) was a measurable share of the render
  // (bench/results/render.md).
  union SlotStorage {
    SlotStorage() {}
    Slot s;
  };
  const Slot& slot(int k) const { return slots_[static_cast<std::size_t>(k)].s; }
  // Fills slot `at` with `l` and its albedo estimates; false for a lobe without a valid shape.
  bool fill_slot(int at, const Lobe& l);
  std::array<SlotStorage, kSlots> slots_;
  int count_ = 0;       // base lobes
  int coat_count_ = 0;  // coat lobes, in the slots after them
  const RadialCorrection* correction_ = nullptr;
  const RadialGrid* grid_ = nullptr;
  bool own_correction_ = false;  // correction_copy_ is the correction (a copy moves with the object)
  RadialCorrection correction_copy_;
  bool transmits_ = false;  // some base lobe transmits, specularly or diffusely
  bool sheen_on_ = false;
  float sheen_roughness_ = 0.0f;
  Rgb sheen_scale_{0.0f};  // C̄ / Σ_k w_k·σ_k (sheen_layer.h)
  float sheen_albedo_ = 0.0f;  // mean(C̄), the sampling choice's albedo estimate without E
};

}  // namespace svbrdf
