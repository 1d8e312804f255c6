#pragma once
// The media a path is inside (KHR_materials_volume): the usual stack of nested and adjacent
// volumes. A path that refracts into a volume's mesh through its front face pushes the volume's
// medium; one that refracts out through a back face removes the topmost entry of that material.
// Between hits, what travels inside is attenuated by Beer–Lambert (CGPP §27.13.1): the
// extension's attenuationColor c is the transmittance after attenuationDistance d, so the
// absorption coefficient is σa = −ln(c)/d per channel, and a segment of length t keeps exp(−σa·t).
// The camera is taken to be outside every volume.
#include <array>

#include "gltf/material_desc.h"

namespace svbrdf {

// σa of a material's volume (0 where attenuationDistance is infinite; +∞ where a channel of
// attenuationColor is 0).
Rgb absorption_coefficient(const MaterialDesc& m);

class MediumStack {
 public:
  static constexpr int kCapacity = 8;  // deeper nesting is ignored (a push that does not fit)

  bool empty() const { return size_ == 0; }
  // The index of refraction the path travels in: the innermost medium's, or 1 outside every volume.
  float ior() const { return size_ > 0 ? items_[size_ - 1].ior : 1.0f; }
  // The index of refraction beyond the boundary of `m`'s volume seen from inside it: the medium the
  // path returns to when it leaves m (the next one out, or 1).
  float ior_outside(const MaterialDesc* m) const;
  // What a segment of length t inside the current medium lets through.
  Rgb transmittance(float t) const;

  // Enters m's volume, whose index is `ior` for the path (the material's, or its index at the
  // wavelength a dispersive path follows).
  void enter(const MaterialDesc* m, float ior);
  void leave(const MaterialDesc* m);

 private:
  struct Medium {
    const MaterialDesc* material = nullptr;
    Rgb sigma_a{0.0f};
    float ior = 1.0f;
  };
  int find(const MaterialDesc* m) const;
  std::array<Medium, kCapacity> items_{};
  int size_ = 0;
};

}  // namespace svbrdf
