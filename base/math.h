#pragma once
// The mathematical constants every module uses, once, in any precision.
#include <numbers>

namespace svbrdf {

template <class T>
inline constexpr T kPiOf = std::numbers::pi_v<T>;
template <class T>
inline constexpr T kInvPiOf = std::numbers::inv_pi_v<T>;

inline constexpr float kPi = kPiOf<float>;
inline constexpr float kInvPi = kInvPiOf<float>;
inline constexpr float kTwoPi = 2.0f * kPiOf<float>;
inline constexpr double kPiD = kPiOf<double>;

// Degrees to radians, in the precision of the argument.
template <class T>
constexpr T radians_of(T degrees) {
  return degrees * (kPiOf<T> / T(180));
}

}  // namespace svbrdf
