#pragma once
// svbrdf-render --frames: frames of a camera the file animates (gltf/animation.h), each written to a
// file of its own. Frame f shows the animation at glTF time f / fps seconds (--fps, default 24). A
// frame is the same image, bit for bit, whether rendered alone, in a range or as tiles on a farm: its
// camera is its time's pose, and its random numbers depend on the seed and its number alone.
#include <cstdint>
#include <string>

#include <glm/glm.hpp>

#include "gltf/scene.h"

namespace svbrdf {

// --fps's default: film's rate.
inline constexpr double kDefaultFps = 24.0;

struct FrameRange {
  int first = 0, last = 0;  // inclusive
  int count() const { return last - first + 1; }
};

// The most frames one range holds: 11.5 hours at 24 frames a second (a longer film renders as
// several ranges); every pose of a range is checked before its first frame renders.
inline constexpr int kMaxFrameCount = 1'000'000;

// "A-B" (A ≤ B, at most kMaxFrameCount frames) or "N", whole numbers from 0 to 2^31 − 2. Throws
// svbrdf::Error (bad input) naming --frames and the text otherwise.
FrameRange parse_frames(const std::string& text);

// The file frame `frame` writes for the output `path`: a run of # in the file's name (not its folder)
// replaced by the frame's number, zero-padded to the run's length (out.####.exr → out.0012.exr;
// a number wider than the run is written whole), else the number padded to 4 digits before the
// extension (out.exr → out.0012.exr). Throws svbrdf::Error (bad input) naming `option` for a name
// with two runs of #.
std::string frame_path(const std::string& path, int frame, const std::string& option);

// The seed of frame `frame` for the render's --seed `seed`: a mix of the two, so that a sequence's
// noise does not stand still on the screen while the picture moves, and a frame's is its own.
std::uint64_t frame_seed(std::uint64_t seed, int frame);

// The glTF time of frame `frame`: frame / fps seconds.
inline double frame_time(int frame, double fps) { return double(frame) / fps; }

// Checks that an animation moves `camera` and that its pose at each frame of `range` places a camera
// (camera_transform_fault). Throws svbrdf::Error (bad input) naming the camera of `scene`, or the
// first frame whose pose is not finite or singular, before any frame is rendered.
void check_frame_poses(const CameraDesc& camera, const FrameRange& range, double fps, const std::string& scene);

// The camera's node-to-world transform at frame `frame` (after check_frame_poses).
glm::dmat4 frame_pose(const CameraDesc& camera, int frame, double fps);

}  // namespace svbrdf
