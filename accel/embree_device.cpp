#include "accel/embree_device.h"

#include "core/error.h"

namespace nx {

EmbreeDevice::EmbreeDevice(const std::string& config) {
  device_ = rtcNewDevice(config.empty() ? nullptr : config.c_str());
  if (!device_)
    throw Error("cannot create the Embree device (error " +
                std::to_string(static_cast<int>(rtcGetDeviceError(nullptr))) + ")");
  rtcSetDeviceErrorFunction(device_, &EmbreeDevice::onError, this);
  rtcSetDeviceMemoryMonitorFunction(device_, &EmbreeDevice::onMemory, this);
}

bool EmbreeDevice::onMemory(void* self, ssize_t bytes, bool) {
  static_cast<EmbreeDevice*>(self)->bytes_.fetch_add(bytes, std::memory_order_relaxed);
  return true; // never refuse: the memory budget is checked before building
}

EmbreeDevice::~EmbreeDevice() {
  rtcReleaseDevice(device_);
}

void EmbreeDevice::onError(void* self, RTCError code, const char* message) {
  auto* d = static_cast<EmbreeDevice*>(self);
  if (d->lastError_.empty())
    d->lastError_ = "Embree error " + std::to_string(static_cast<int>(code)) + ": " +
                    (message ? message : "(no message)");
}

void EmbreeDevice::throwIfError(const std::string& context) {
  if (lastError_.empty()) return;
  const std::string message = context + ": " + lastError_;
  lastError_.clear();
  throw Error(message);
}

} // namespace nx
