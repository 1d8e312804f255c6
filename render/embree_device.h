#pragma once
// One Embree 3 device per process, created with an error callback that turns Embree's errors into
// svbrdf::Error instead of silent failures.
#include <embree3/rtcore.h>

namespace svbrdf {

class EmbreeDevice {
 public:
  EmbreeDevice();
  ~EmbreeDevice();
  EmbreeDevice(const EmbreeDevice&) = delete;
  EmbreeDevice& operator=(const EmbreeDevice&) = delete;

  RTCDevice get() const { return device_; }

 private:
  RTCDevice device_ = nullptr;
};

// Embree wants flush-to-zero and denormals-are-zero in every thread that traces
// (DEPENDENCIES.md pitfall 6); call at the start of each worker's task.
void set_denormals_zero();

}  // namespace svbrdf
