#pragma once
// The media a path is inside, as a stack: crossing into a closed shape pushes the medium that
// fills it (or "none" for a shape without one, e.g. a glass shell), crossing out pops it. Shapes
// nested inside each other (a liquid in a glass in air) thus need no declared "outside"
// medium. Fixed size, no allocation.

#include <cstdint>

namespace nx {

/// Media entered along a path, innermost last.
class MediumStack {
public:
  /// Nesting deeper than this keeps the innermost levels' count but not their media.
  static constexpr int kMaxDepth = 8;

  /// The medium the path is in: the innermost entered shape's, or -1 (none).
  int current() const { return depth_ > 0 && depth_ <= kMaxDepth ? ids_[depth_ - 1] : -1; }
  /// Enters a shape filled with `medium` (-1: a shape without a medium).
  void enter(int medium) {
    if (depth_ < kMaxDepth) ids_[depth_] = static_cast<int16_t>(medium);
    ++depth_;
  }
  /// Leaves the innermost shape (a stray exit, from rounding at a boundary, is ignored).
  void leave() {
    if (depth_ > 0) --depth_;
  }
  /// Number of shapes the path is inside.
  int depth() const { return depth_; }

private:
  int16_t ids_[kMaxDepth] = {};
  int depth_ = 0;
};

} // namespace nx
