#pragma once
// glTF 2.0 animation (§3.11 and Appendix C) as far as a render needs it: the node that places a
// camera, and its ancestors, moved over time by translation, rotation and scale channels. A sampler
// maps a time in seconds to a value by its key times and interpolation: LINEAR (rotations by
// spherical linear interpolation of unit quaternions), STEP, or CUBICSPLINE (a cubic Hermite spline
// with the file's tangents). Before the first key a sampler holds the first key's value, after the
// last key the last's (§3.11: "output MUST be clamped to the nearest end of the input range").
// Read from the file by gltf/animation_reader.h; meshes and lights keep their static pose.
#include <array>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

namespace svbrdf {

enum class Interpolation { linear, step, cubic_spline };

// One animation sampler with its accessors read and checked: key times strictly increasing from
// ≥ 0, and `components` values per output element (3 for a translation or a scale, 4 for a rotation
// quaternion in glTF's x, y, z, w order). LINEAR and STEP have one element per key; CUBICSPLINE three,
// in the order in-tangent, value, out-tangent, and at least two keys.
struct AnimationSampler {
  Interpolation interpolation = Interpolation::linear;
  int components = 3;
  std::vector<float> times;
  std::vector<float> values;
};

// The sampler's value at time `t` seconds, `components` numbers (the rest 0). A rotation
// (components 4) is a unit quaternion: LINEAR interpolates it by slerp, CUBICSPLINE component by
// component and then normalises (Appendix C).
std::array<double, 4> sample(const AnimationSampler& sampler, double t);

// Spherical linear interpolation of unit quaternions a and b by u ∈ [0, 1] along the shorter arc
// (b and −b are the same rotation): the rotation that turns at a constant rate from a to b.
glm::dquat slerp_unit(const glm::dquat& a, const glm::dquat& b, double u);

// One node of a camera's chain: its own transform (the file's matrix, or its translation, rotation
// and scale) and the samplers that animate its translation, rotation or scale. glTF animates only
// nodes given by translation, rotation and scale (§3.11: a targeted node has no matrix).
struct NodeMotion {
  int node = -1;
  std::optional<glm::dmat4> matrix;
  glm::dvec3 translation{0.0};
  glm::dquat rotation{1.0, 0.0, 0.0, 0.0};  // unit
  glm::dvec3 scale{1.0};
  std::optional<AnimationSampler> translation_sampler, rotation_sampler, scale_sampler;

  // The node's local transform at time t: T · R · S of its values at t (§3.5.2).
  glm::dmat4 local(double t) const;
};

// The nodes from a scene's root down to the node that carries a camera, with what animates them.
struct CameraMotion {
  std::vector<NodeMotion> chain;  // the root first, the camera's node last
  // Each channel that moves the chain, as "animations[0].channels[2]", in the file's order.
  std::vector<std::string> channels;

  bool animated() const { return !channels.empty(); }
  // The camera's node-to-world transform at time t: the product of the chain's local transforms.
  glm::dmat4 to_world(double t) const;
};

// Why `world` cannot place a camera, or null when it can: finite (no entry beyond 1e18) and
// invertible in its upper 3×3 (glTF 2.0 §3.10.1 asks for no scale on a camera node; a zero scale
// would give rays no direction). The text continues "places cameras[i] ", e.g. "with a singular ...".
const char* camera_transform_fault(const glm::dmat4& world);

}  // namespace svbrdf
