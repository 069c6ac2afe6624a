#pragma once
// Ownership of the Embree device that every acceleration structure lives in.

#include <embree3/rtcore.h>

#include <atomic>
#include <cstdint>
#include <string>

namespace nx {

/// An Embree 3 device (RAII). Embree errors reported through its callback are kept so that
/// callers can turn them into nx::Error with takeError().
class EmbreeDevice {
public:
  /// Creates a device with the given Embree configuration string ("" for defaults).
  explicit EmbreeDevice(const std::string& config = "");
  ~EmbreeDevice();
  EmbreeDevice(const EmbreeDevice&) = delete;
  EmbreeDevice& operator=(const EmbreeDevice&) = delete;

  /// The raw device handle.
  RTCDevice handle() const { return device_; }
  /// Throws nx::Error if Embree reported an error since the last call, naming `context`.
  void throwIfError(const std::string& context);
  /// Bytes Embree holds now (its memory monitor's running sum).
  int64_t bytesInUse() const { return bytes_.load(std::memory_order_relaxed); }

private:
  static void onError(void* self, RTCError code, const char* message);
  static bool onMemory(void* self, ssize_t bytes, bool post);
  std::atomic<int64_t> bytes_{0};
  RTCDevice device_ = nullptr;
  std::string lastError_;
};

} // namespace nx
