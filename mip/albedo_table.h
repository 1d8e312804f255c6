#pragma once
// Private to mip/: included by mip's .cpp files only (lobe_reduction.h is the reduction's public face).
// The specular albedo of a lobe, which every merge keeps (keep_specular_flux, lobe_reduction.cpp).
#include <algorithm>
#include <array>
#include <cmath>

#include "base/series_log.h"
#include "mip/lobe.h"

namespace svbrdf::reduction {

// The specular albedo of a flat lobe, ∫ D·V·(F0 + (F90 − F0)·w)·wo.z dωo = F0·a(α², θi) + (F90 − F0)·b(α², θi),
// summed over θi ∈ {0°, 45°, 75°}, tabulated over log α² by quadrature (wo from GGX half vectors,
// stratified). GGX with the glTF visibility loses energy as α grows (single scattering), so merging a
// rough lobe into a sharp one would add flux; merges rescale the specular part to keep this albedo.
class SpecAlbedoTable {
 public:
  static const SpecAlbedoTable& get();
  double albedo(double alpha2, double f0, double ggx, double f90 = 1) const {
    return albedo_at_log(series_log(std::clamp(alpha2, kMin, 1.0)), f0, ggx, f90);
  }
  // The same at ln α² (clamped to the table).
  double albedo_at_log(double ln_alpha2, double f0, double ggx, double f90 = 1) const {
    const Cell c = cell(ln_alpha2);
    return ggx * (f0 * c.at(a_) + (f90 - f0) * c.at(b_)) + (1 - ggx) * (f0 * c.at(ba_) + (f90 - f0) * c.at(bb_));
  }
  // The same for μ = 1 (a GGX lobe; a roughness mixture's components), without the Beckmann columns.
  double ggx_albedo_at_log(double ln_alpha2, double f0, double f90 = 1) const {
    const Cell c = cell(ln_alpha2);
    return f0 * c.at(a_) + (f90 - f0) * c.at(b_);
  }

 private:
  static constexpr int kSize = 128;
  static constexpr double kMin = 1e-6;
  // Where ln α² falls in the table: entry i and the share t of entry i + 1.
  struct Cell {
    int i;
    double t;
    double at(const std::array<double, kSize>& v) const {
      return v[static_cast<std::size_t>(i)] * (1 - t) + v[static_cast<std::size_t>(i + 1)] * t;
    }
  };
  static Cell cell(double ln_alpha2) {
    const double lmin = std::log(kMin);
    const double x = (std::clamp(ln_alpha2, lmin, 0.0) - lmin) / (-lmin) * (kSize - 1);
    const int i = std::min(kSize - 2, static_cast<int>(x));
    return {i, x - i};
  }
  SpecAlbedoTable();
  std::array<double, kSize> a_{}, b_{}, ba_{}, bb_{};  // GGX and Beckmann columns
};

// A lobe's specular flux as the merges keep it: weight · |mean normal| · its specular albedo (the
// table's, summed over θi ∈ {0°, 45°, 75°}); a roughness mixture's is the mean of its components'.
double specular_flux(const Lobe& lobe);
// A lobe's transmitted flux as the merges keep it (lobe.h "Transmission"): weight · |mean normal| · the
// table's albedo of its transmission shape (GGX of transmission_alpha2 or its band, its stretch as specular_flux
// takes it) with τ, τ90 for F0, F90 — the BTDF is the reflection of the mirrored direction, so it
// transmits what that lobe would reflect. 0 without a transmission.
double transmission_flux(const Lobe& lobe);

}  // namespace svbrdf::reduction
