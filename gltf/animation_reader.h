#pragma once
// Reading, from a glTF document, the animations that move a camera (gltf/animation.h): the channels
// of the file's animations whose target is the camera's node or one of its ancestors, by
// translation, rotation or scale, and their samplers, each checked (glTF 2.0 §3.11, §5.4–5.6): the
// sampler exists; its interpolation is LINEAR, STEP or CUBICSPLINE; its input is a SCALAR FLOAT
// accessor of times ≥ 0 that increase strictly; its output a FLOAT VEC3 (translation, scale) or a
// FLOAT or normalized-integer VEC4 (rotation) accessor with one element per key (three for
// CUBICSPLINE, which needs two keys or more), and no zero quaternion. Every accessor is read through
// gltf/accessor.h, bounds checked. Channels that target other nodes are not read: a mesh, a light or
// a morph target keeps its static pose.
#include <string>
#include <vector>

#include "gltf/animation.h"
#include "gltf/document.h"

namespace svbrdf::gltf {

// The motion of `chain` (node indices: a scene's root first, the camera's node last; their own
// transforms already checked, as the scene reader does). Throws svbrdf::Error (bad input) in one line
// "FILE: animations[a].channels[c].sampler: ..." or "FILE: animations[a].samplers[s].input: ..." for a
// fault in what it reads. Two channels of one animation that animate one property of one node are a
// fault (§3.11); when two animations do, the first is played and `warnings` gets a line.
CameraMotion read_camera_motion(const Document& doc, const std::vector<int>& chain, std::vector<std::string>* warnings);

}  // namespace svbrdf::gltf
