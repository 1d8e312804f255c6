#include "apps/render_frames.h"

#include <climits>
#include <cstdio>
#include <filesystem>

#include "appearance/rng.h"
#include "base/error.h"
#include "gltf/animation.h"

namespace svbrdf {

namespace fs = std::filesystem;

namespace {

// The largest frame number: a range of frames × tiles still numbers Slurm's array tasks in an int.
constexpr long long kMaxFrame = INT_MAX - 1;

std::string padded(int frame, std::size_t width) {
  std::string digits = std::to_string(frame);
  if (digits.size() < width) digits.insert(0, width - digits.size(), '0');
  return digits;
}

std::string seconds_text(double t) {
  char b[32];
  std::snprintf(b, sizeof b, "%.6g", t);
  return b;
}

}  // namespace

FrameRange parse_frames(const std::string& text) {
  const auto whole = [&](const std::string& part) -> long long {
    if (part.empty() || part.size() > 10 || part.find_first_not_of("0123456789") != std::string::npos) {
      if (!part.empty() && part[0] == '-' && part.size() > 1 && part.find_first_not_of("0123456789", 1) == std::string::npos)
        throw input_error("--frames " + text, "frame numbers are 0 or more");
      throw input_error("--frames " + text, "expected A-B (frames A to B) or N (frame N), whole numbers, e.g. 0-47");
    }
    const long long v = std::stoll(part);
    if (v > kMaxFrame) throw input_error("--frames " + text, "a frame number above " + std::to_string(kMaxFrame));
    return v;
  };
  // A leading '-' is a negative number, not the range's dash.
  const std::size_t dash = text.find('-', 1);
  if (dash == std::string::npos) {
    const int n = int(whole(text));
    return {n, n};
  }
  const FrameRange r{int(whole(text.substr(0, dash))), int(whole(text.substr(dash + 1)))};
  if (r.first > r.last)
    throw input_error("--frames " + text, "the first frame comes after the last; write the range from first to last");
  if (r.count() > kMaxFrameCount)
    throw input_error("--frames " + text, "more than " + std::to_string(kMaxFrameCount) +
                                              " frames in one range; render a long sequence as several ranges");
  return r;
}

std::string frame_path(const std::string& path, int frame, const std::string& option) {
  const fs::path p(path);
  const std::string name = p.filename().string();
  const std::size_t run = name.find('#');
  std::string named;
  if (run == std::string::npos) {
    named = p.stem().string() + "." + padded(frame, 4) + p.extension().string();
  } else {
    const std::size_t end = std::min(name.find_first_not_of('#', run), name.size());
    if (name.find('#', end) != std::string::npos)
      throw input_error(option + " " + path, "has two runs of # in its name; one says where the frame number goes");
    named = name.substr(0, run) + padded(frame, end - run) + name.substr(end);
  }
  return p.has_parent_path() ? (p.parent_path() / named).string() : named;
}

std::uint64_t frame_seed(std::uint64_t seed, int frame) {
  return mix64(seed ^ mix64(0x9E3779B97F4A7C15ULL * (std::uint64_t(frame) + 1)));
}

void check_frame_poses(const CameraDesc& camera, const FrameRange& range, double fps, const std::string& scene) {
  if (!camera.motion)
    throw input_error("--frames",
                      camera.node < 0 ? scene + " has no camera, and the framing camera does not move; render without --frames"
                                      : "no animation of " + scene + " moves camera '" + camera.name +
                                            "' (its node nor an ancestor); render without --frames");
  for (int f = range.first;; ++f) {
    if (const char* fault = camera_transform_fault(frame_pose(camera, f, fps)))
      throw input_error(scene + ": nodes[" + std::to_string(camera.node) + "]",
                        "at frame " + std::to_string(f) + " (t = " + seconds_text(frame_time(f, fps)) +
                            " s) the animation places camera '" + camera.name + "' " + fault);
    if (f == range.last) break;
  }
}

glm::dmat4 frame_pose(const CameraDesc& camera, int frame, double fps) {
  return camera.motion->to_world(frame_time(frame, fps));
}

}  // namespace svbrdf
