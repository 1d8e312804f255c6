#include "mip/reduction_numerics.h"

#include <algorithm>
#include <cmath>

namespace svbrdf::reduction {

double scaled_bessel_i0(double x) {
  if (x <= 3.75) {
    const double t2 = (x / 3.75) * (x / 3.75);
    return double(series_exp(static_cast<float>(-x))) *
           (1.0 + t2 * (3.5156229 + t2 * (3.0899424 + t2 * (1.2067492 + t2 * (0.2659732 + t2 * (0.0360768 + t2 * 0.0045813))))));
  }
  const double s = 3.75 / x;
  return (0.39894228 + s * (0.01328592 + s * (0.00225319 + s * (-0.00157565 + s * (0.00916281 + s * (-0.02057706 +
          s * (0.02635537 + s * (-0.01647633 + s * 0.00392377)))))))) / std::sqrt(x);
}

const SinhcInverse& SinhcInverse::get() {
  static const SinhcInverse t;
  return t;
}

double SinhcInverse::guess(double target) const {
  const double w = series_log(1.0 + std::sqrt(std::max(0.0, target - 1.0)));
  if (!(w < kMaxW)) return std::log(2.0 * target * std::log(2.0 * target + 1.0) + 1.0);
  const double x = w / kMaxW * (kSize - 1);
  const int i = std::min(kSize - 2, static_cast<int>(x));
  const double t = x - i;
  return u_[static_cast<std::size_t>(i)] * (1 - t) + u_[static_cast<std::size_t>(i + 1)] * t;
}

SinhcInverse::SinhcInverse() {
  for (int k = 0; k < kSize; ++k) {
    const double v = std::expm1(kMaxW * k / (kSize - 1)), target = 1.0 + v * v;
    double lo = 0, hi = 20;
    for (int it = 0; it < 80; ++it) {
      const double mid = 0.5 * (lo + hi);
      (mid > 0 && std::sinh(mid) / mid < target ? lo : hi) = mid;
    }
    u_[static_cast<std::size_t>(k)] = 0.5 * (lo + hi);
  }
}

}  // namespace svbrdf::reduction
