#include "render/embree_device.h"

#include <cstdio>
#include <pmmintrin.h>
#include <string>
#include <xmmintrin.h>

#include "base/error.h"

namespace svbrdf {

namespace {
void on_embree_error(void*, RTCError code, const char* message) {
  // Callers check rtcGetDeviceError where it matters; the text goes to stderr so it is never lost.
  if (code != RTC_ERROR_NONE) std::fprintf(stderr, "embree: %s\n", message ? message : "unknown error");
}
}  // namespace

EmbreeDevice::EmbreeDevice() {
  device_ = rtcNewDevice("verbose=0");
  if (!device_) {
    throw Error("Embree: cannot create a device (error " + std::to_string(rtcGetDeviceError(nullptr)) + ")",
                Error::Kind::internal);
  }
  rtcSetDeviceErrorFunction(device_, on_embree_error, nullptr);
}

EmbreeDevice::~EmbreeDevice() { rtcReleaseDevice(device_); }

void set_denormals_zero() {
  _MM_SET_FLUSH_ZERO_MODE(_MM_FLUSH_ZERO_ON);
  _MM_SET_DENORMALS_ZERO_MODE(_MM_DENORMALS_ZERO_ON);
}

}  // namespace svbrdf
