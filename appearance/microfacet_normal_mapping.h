#pragma once
// Microfacet-based normal mapping (Schüssler, Heitz, Hanika, Dachsbacher 2017, "Microfacet-based
// Normal Mapping for Robust Monte Carlo Path Tracing", ACM TOG 36(6)): a normal-mapped point is
// shaded as a microsurface of two facets instead of by the inner BSDF turned to the mapped normal.
// The perturbed facet wp carries the inner BSDF; the tangent facet wt, perpendicular to the
// geometric normal wg and facing away from wp's tilt, is a perfect mirror. Their areas make the
// microsurface's mean normal wg, so it is a height field: light that reaches the geometric surface
// reaches a facet (no black crescent where wp turns away from a light that wg sees), and what the
// facets scatter stays in the microsurface until it leaves (no energy is lost or made).
//
// Frames. Every direction given to or returned by this Bsdf is in the geometric frame (z = wg,
// x = the geometric tangent), wi toward the light, wo toward the viewer. The inner BSDF is queried
// in its own frame, perturbed_frame(): z = wp, x = the geometric tangent made perpendicular to wp
// (Gram–Schmidt), so an anisotropic inner model keeps its orientation as closely as wp allows.
//
// eval and pdf: every light path with one scattering on wp, written from the viewer's side: the
// paper's explicit evaluation
//   wo → wp → wi,   wo → wp → wt → wi,   wo → wt → wp → wi,
// and wo → wt → wp → wt → wi, as exact in closed form. With it every wi and wo above the geometric
// plane are joined by some path (each sees wp or wt), so a delta light, which only eval reaches,
// leaves no texel black for a viewer that sees only wt.
// pdf(wi, wo) is the exact density with which sample() returns these paths as finite samples.
//
// sample: the paper's random walk. The viewer's ray picks wp or wt with the intersection
// probabilities λp(wo), λt(wo); on wp the inner model samples the next direction, on wt the ray is
// mirrored; after each event it leaves with probability G1 and hits the other facet otherwise. The
// result is reported in two kinds:
//   - a walk that took one of the four explicit paths through a finite inner sample: finite, with
//     pdf = pdf(wi, wo) and weight = eval(wi, wo)·cosθi / pdf(wi, wo) (one-sample MIS over the
//     four paths, so a sample's weight is the same whichever of them produced it);
//   - every other walk (a second scattering on wp, an impulse of the inner model):
//     SampleKind::impulse, weight = the walk's throughput, pdf = the probability of its
//     discrete choices (facets, escapes, the inner model's impulse choices; floored at FLT_MIN).
//     These directions are no delta lobe, but like an impulse they are outside eval: light sampling
//     never finds them, so a path tracer must count them with full weight and no MIS — which the
//     integrator does for impulses. Next-event estimation (eval) plus these samples estimate the
//     whole microsurface BSDF without bias.
// Why the sum keeps energy: the mirror reflects everything; the choice of facet and the choice
// between leaving and hitting the other facet are made with their probabilities, so a walk's
// throughput is the product of the inner model's sample weights alone. With a white inner model
// that never absorbs, every walk that leaves carries weight 1: the directional albedo is 1, less
// only what the bound on the walk cuts (kMaxWpEvents). After a Lambertian scattering on wp the
// light leaves before the next one with probability <wp, wg> (in a white furnace the wp facets,
// of area 1/<wp, wg>, emit π L/<wp, wg> and π L leaves), so the walk takes 1/<wp, wg> events on
// wp on average. eval holds the part of this that light sampling can find, the light that leaves
// after the first event on wp: for a white Lambert inner model <wp, wg> of the albedo for every viewer (0.87 at wp 30° from wg, 0.50 at
// 60°, 0.17 at 80°), since every path with two scatterings on wp is the walk's alone. Under a delta
// light (point, spot, directional), which only light sampling reaches, that remainder is missing:
// the model is darker there than under area or environment light, but nowhere black.
//
// Approximations:
//   - <wp, wg> is clamped to at least kMinCosWp (wp turned toward wg in the plane of wg and wp):
//     the microsurface flattens into vertical facets as <wp, wg> → 0, a_p, a_t grow as
//     1/<wp, wg>, and the walk's length with them. A wp below the geometric horizon is clamped the
//     same way; a wp opposite wg (no tilt direction) or not finite is taken as wg.
//   - Transmission: an inner direction below wp's plane (a dielectric's refraction, a BTDF) leaves
//     the microsurface at once, unmasked below the surface; eval and pdf hold no transmission.
//   - impulses_in/out list the inner model's impulses through the four explicit paths (with the
//     same λ and G1 factors as eval) and keep the two strongest, since Impulses holds two; walks
//     through more events are only sampled.
//   - scatter_probability(wo) is the energy split of the first event on wp (λp P(wo) + λt P(wo
//     mirrored on wt), P the inner model's): sample() is absorbed when u.x is beyond it, as bsdf.h
//     asks; later events on wp use the inner model's own split, so a walk may still be absorbed.
//   - wo or wi below the geometric horizon: zero, absorbed (the model is a BRDF of the upper side).
//
// wp = wg: every call is forwarded to the inner model unchanged.
#include "appearance/bsdf.h"
#include "appearance/frame.h"

namespace svbrdf {

class MicrofacetNormalMapping final : public Bsdf {
 public:
  // The smallest <wp, wg> kept (about 87°).
  static constexpr float kMinCosWp = 0.05f;
  // The bound on the random walk: scatterings on wp. A Lambertian scattering on wp is the last with
  // probability <wp, wg>, so at the clamp 0.95^256 ≈ 2e-6 of the energy is cut.
  static constexpr int kMaxWpEvents = 256;

  // `inner` works in perturbed_frame() and must outlive this object. `wp` is the perturbed normal
  // in the geometric frame (z = wg); it need not be normalized.
  MicrofacetNormalMapping(const Bsdf& inner, const glm::vec3& wp);

  Rgb eval(const glm::vec3& wi, const glm::vec3& wo) const override;
  Impulses impulses_in(const glm::vec3& wo) const override;
  Impulses impulses_out(const glm::vec3& wi) const override;
  BsdfSample sample(const glm::vec3& wo, const SampleU& u) const override;
  float pdf(const glm::vec3& wi, const glm::vec3& wo) const override;
  float scatter_probability(const glm::vec3& wo) const override;

  // The inner model's frame in geometric coordinates: n = wp after the clamp.
  const Frame& perturbed_frame() const { return frame_p_; }
  // The tangent facet's normal in geometric coordinates (undefined when passes_through()).
  const glm::vec3& wt() const { return wt_; }
  // True when wp = wg: the inner model unchanged.
  bool passes_through() const { return pass_through_; }

 private:
  glm::vec3 to_p(const glm::vec3& w) const { return frame_p_.to_local(w); }
  glm::vec3 from_p(const glm::vec3& w) const { return frame_p_.to_world(w); }
  glm::vec3 mirror_t(const glm::vec3& w) const;
  float lambda_p(const glm::vec3& w) const;
  float visible_area(const glm::vec3& w) const;
  float masking(const glm::vec3& w, const glm::vec3& wm) const;
  float masking_over_cos(const glm::vec3& w, const glm::vec3& wm) const;
  float blocked_cos(const glm::vec3& wi) const;

  const Bsdf& inner_;
  Frame frame_p_;
  glm::vec3 wt_{-1.0f, 0.0f, 0.0f};
  float cos_p_ = 1.0f, sin_p_ = 0.0f;
  bool pass_through_ = true;
};

}  // namespace svbrdf
