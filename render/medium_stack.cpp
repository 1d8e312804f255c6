#include "render/medium_stack.h"

#include <cmath>
#include <limits>

namespace svbrdf {

Rgb absorption_coefficient(const MaterialDesc& m) {
  Rgb s(0.0f);
  if (!std::isfinite(m.attenuation_distance)) return s;
  for (int c = 0; c < 3; ++c)
    s[c] = m.attenuation_color[c] > 0.0f ? -std::log(m.attenuation_color[c]) / m.attenuation_distance
                                         : std::numeric_limits<float>::infinity();
  return s;
}

int MediumStack::find(const MaterialDesc* m) const {
  for (int i = size_ - 1; i >= 0; --i)
    if (items_[std::size_t(i)].material == m) return i;
  return -1;
}

float MediumStack::ior_outside(const MaterialDesc* m) const {
  const int i = find(m);
  if (i < 0) return ior();  // not inside m by the stack's account: the path's own medium
  return i > 0 ? items_[std::size_t(i - 1)].ior : 1.0f;
}

Rgb MediumStack::transmittance(float t) const {
  if (size_ == 0 || !(t > 0.0f)) return Rgb(1.0f);
  const Rgb& s = items_[std::size_t(size_ - 1)].sigma_a;
  return {std::exp(-s.x * t), std::exp(-s.y * t), std::exp(-s.z * t)};
}

void MediumStack::enter(const MaterialDesc* m, float ior) {
  if (size_ >= kCapacity) return;
  items_[std::size_t(size_++)] = {m, absorption_coefficient(*m), ior};
}

void MediumStack::leave(const MaterialDesc* m) {
  const int i = find(m);
  if (i < 0) return;
  for (int k = i; k + 1 < size_; ++k) items_[std::size_t(k)] = items_[std::size_t(k + 1)];
  --size_;
}

}  // namespace svbrdf
