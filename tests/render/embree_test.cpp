#include <embree3/rtcore.h>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "render/embree_device.h"

namespace svbrdf {
namespace {

// One triangle in the z = 2 plane; a ray from the origin along +z hits it at t = 2 with the
// barycentrics of the hit point, and a ray beside it misses.
TEST(Embree, RayHitsTriangleAtKnownDistance) {
  EmbreeDevice device;
  RTCScene scene = rtcNewScene(device.get());
  RTCGeometry geom = rtcNewGeometry(device.get(), RTC_GEOMETRY_TYPE_TRIANGLE);
  auto* v = static_cast<float*>(
      rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), 3));
  const float verts[9] = {-1, -1, 2, 3, -1, 2, -1, 3, 2};
  for (int i = 0; i < 9; ++i) v[i] = verts[i];
  auto* idx = static_cast<unsigned*>(
      rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), 1));
  idx[0] = 0, idx[1] = 1, idx[2] = 2;
  rtcCommitGeometry(geom);
  rtcAttachGeometry(scene, geom);
  rtcReleaseGeometry(geom);
  rtcCommitScene(scene);
  ASSERT_EQ(rtcGetDeviceError(device.get()), RTC_ERROR_NONE);

  auto trace = [&](float ox, float oy) {
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    RTCRayHit rh{};
    rh.ray.org_x = ox, rh.ray.org_y = oy, rh.ray.org_z = 0;
    rh.ray.dir_x = 0, rh.ray.dir_y = 0, rh.ray.dir_z = 1;
    rh.ray.tnear = 0, rh.ray.tfar = std::numeric_limits<float>::infinity();
    rh.ray.mask = ~0u;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(scene, &ctx, &rh);
    return rh;
  };
  const RTCRayHit hit = trace(0, 0);
  ASSERT_NE(hit.hit.geomID, RTC_INVALID_GEOMETRY_ID);
  EXPECT_NEAR(hit.ray.tfar, 2.0f, 1e-5);
  // p = v0 + u (v1 - v0) + v (v2 - v0): (0,0) = (-1,-1) + u (4,0) + v (0,4) → u = v = 1/4.
  EXPECT_NEAR(hit.hit.u, 0.25f, 1e-5);
  EXPECT_NEAR(hit.hit.v, 0.25f, 1e-5);
  // The geometric normal of a counter-clockwise triangle seen from -z points toward +z (e1 × e2).
  EXPECT_GT(hit.hit.Ng_z, 0.0f);
  EXPECT_EQ(trace(2.5f, 2.5f).hit.geomID, RTC_INVALID_GEOMETRY_ID) << "outside the hypotenuse";
  rtcReleaseScene(scene);
}

}  // namespace
}  // namespace svbrdf
