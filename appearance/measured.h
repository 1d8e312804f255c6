#pragma once
// A measured isotropic BRDF in the MERL layout (Matusik et al. 2003, "A Data-Driven Reflectance
// Model"; brdf-models.md): three int32 dimensions 90, 90, 180, then 3 × 90·90·180 doubles, channel
// planes R, G, B, scaled by 1/1500, 1.15/1500, 1.66/1500. Bins are indexed by the half/difference
// angles of Rusinkiewicz 1998: θh with the square-root mapping i = ⌊90·sqrt(θh/(π/2))⌋,
// θd linearly (1° bins), φd over [0, π) (1° bins). Negative entries (unmeasured) read as 0.
//
// Reciprocity (§27.6): swapping wi and wo keeps (θh, θd) and moves φd to φd + π, which the layout
// folds onto the same bin, so each table cell is its own reciprocal partner and the projection
// "average f(wi, wo) and f(wo, wi)" changes no stored value. What it still has to catch is
// numerical: directions whose two orders round into neighbouring bins. eval therefore returns
// the average of the two lookups, which makes f(wi, wo) = f(wo, wi) exact.
//
// Sampling (the documented choice): cosine-weighted, never absorbing by choice (the albedo of a
// table is unknown); a weak sampler for glossy tables, the weight f·cosθ/p corrects it.
#include <filesystem>
#include <memory>
#include <vector>

#include "appearance/bsdf.h"

namespace svbrdf {

class MerlTable {
 public:
  static constexpr int kThetaH = 90, kThetaD = 90, kPhiD = 180;
  static constexpr int kCells = kThetaH * kThetaD * kPhiD;
  static constexpr double kScale[3] = {1.0 / 1500.0, 1.15 / 1500.0, 1.66 / 1500.0};

  MerlTable();  // all zero

  // Throws svbrdf::Error (naming the file) for a missing, truncated or malformed file.
  static MerlTable read(const std::filesystem::path& path);
  // Written atomically (base/atomic_file.h).
  void write(const std::filesystem::path& path) const;
  // The table of an analytic model: f at each bin's center configuration.
  static MerlTable tabulate(const Bsdf& bsdf);

  static int cell(int theta_h, int theta_d, int phi_d) { return phi_d + kPhiD * (theta_d + kThetaD * theta_h); }
  // The bin of a direction pair (both above the horizon).
  static int cell_of(const glm::vec3& wi, const glm::vec3& wo);
  // The center configuration of a bin, as a direction pair (φh = 0).
  static void center_directions(int theta_h, int theta_d, int phi_d, glm::vec3& wi, glm::vec3& wo);

  Rgb at(int cell) const;  // f of a cell
  void set(int cell, const Rgb& f);
  // Nearest-bin lookup, no symmetrization; 0 below either horizon.
  Rgb lookup(const glm::vec3& wi, const glm::vec3& wo) const;

 private:
  std::vector<float> f_;  // RGB interleaved per cell (one cache line a lookup), already scaled to f
};

class Measured final : public Bsdf {
 public:
  explicit Measured(std::shared_ptr<const MerlTable> table);
  Rgb eval(const glm::vec3& wi, const glm::vec3& wo) const override;
  BsdfSample sample(const glm::vec3& wo, const SampleU& u) const override;
  float pdf(const glm::vec3& wi, const glm::vec3& wo) const override;

 private:
  std::shared_ptr<const MerlTable> table_;
};

}  // namespace svbrdf
