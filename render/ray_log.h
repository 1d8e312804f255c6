#pragma once
// An optional record of every ray the integrator traces (closest-hit and shadow), per thread, so the
// benchmark can replay exactly the renderer's rays through raw Embree and measure what shading and
// texturing cost on top of traversal. Off (null) in normal renders.
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>
#include <tbb/enumerable_thread_specific.h>

namespace svbrdf {

struct RecordedRay {
  glm::vec3 origin;
  float tnear;
  glm::vec3 dir;
  float tfar;
  std::uint64_t seed;  // stochastic-opacity seed the renderer passed
  bool shadow;         // an occlusion query
};

class RayLog {
 public:
  void record(const glm::vec3& o, const glm::vec3& d, float tnear, float tfar, std::uint64_t seed, bool shadow) {
    per_thread_.local().push_back({o, tnear, d, tfar, seed, shadow});
  }
  // All rays, thread by thread (the order within a thread is the order traced).
  std::vector<RecordedRay> gather() const {
    std::vector<RecordedRay> all;
    for (const auto& v : per_thread_) all.insert(all.end(), v.begin(), v.end());
    return all;
  }

 private:
  tbb::enumerable_thread_specific<std::vector<RecordedRay>> per_thread_;
};

}  // namespace svbrdf
