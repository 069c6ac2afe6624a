#pragma once
// The floating-point mode renders run in: flush-to-zero and denormals-are-zero (the mode
// Embree asks its callers for). Set explicitly so an image does not depend on the state of the
// thread that started the render (a command line's main thread, a Python worker thread).

#if defined(__SSE__) || defined(__x86_64__)
#include <xmmintrin.h>
#endif

namespace nx {

/// Sets FTZ and DAZ on the calling thread for its lifetime, then restores the previous mode.
class FlushDenormalsScope {
public:
  FlushDenormalsScope() {
#if defined(__SSE__) || defined(__x86_64__)
    saved_ = _mm_getcsr();
    _mm_setcsr(saved_ | 0x8040u); // FTZ (bit 15) | DAZ (bit 6)
#endif
  }
  ~FlushDenormalsScope() {
#if defined(__SSE__) || defined(__x86_64__)
    _mm_setcsr(saved_);
#endif
  }
  FlushDenormalsScope(const FlushDenormalsScope&) = delete;
  FlushDenormalsScope& operator=(const FlushDenormalsScope&) = delete;

private:
  unsigned saved_ = 0;
};

} // namespace nx
