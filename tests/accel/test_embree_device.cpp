#include <gtest/gtest.h>

#include "accel/embree_device.h"
#include "core/error.h"

namespace nx {
namespace {

TEST(EmbreeDevice, CreatesAndReportsErrors) {
  EmbreeDevice device;
  ASSERT_NE(device.handle(), nullptr);
  EXPECT_NO_THROW(device.throwIfError("idle"));
  // An invalid argument is reported through the callback and turned into nx::Error.
  rtcSetSceneBuildQuality(nullptr, RTC_BUILD_QUALITY_HIGH);
  RTCScene scene = rtcNewScene(device.handle());
  rtcAttachGeometryByID(scene, nullptr, 0);
  EXPECT_THROW(device.throwIfError("attaching"), Error);
  EXPECT_NO_THROW(device.throwIfError("after"));
  rtcReleaseScene(scene);
}

} // namespace
} // namespace nx
