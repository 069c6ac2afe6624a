#pragma once
// Bilinear lookup in a grid of texels by surface coordinates: (u, v) = (0, 0) the grid's
// bottom-left corner, (1, 1) its top-right, row 0 at the top; texel centres at (i + 1/2) / width;
// beyond [0, 1] the edge texels continue.

#include "core/cell_index.h"
#include <algorithm>
#include <cmath>
#include <cstddef>

namespace nx {

/// The four texels around a point (row * width + column) and their bilinear weights.
struct BilinearTexels {
  size_t texel[4];
  float weight[4];
};

/// The texels of a width x height grid around (u, v).
inline BilinearTexels bilinearTexels(float u, float v, int width, int height) {
  const float x = u * static_cast<float>(width) - 0.5f;
  const float y = (1 - v) * static_cast<float>(height) - 0.5f;
  const float fx0 = std::floor(x), fy0 = std::floor(y);
  const float ax = x - fx0, ay = y - fy0;
  auto clampX = [&](float c) { return cellIndex(c, width); };
  auto clampY = [&](float c) { return cellIndex(c, height); };
  const int x0 = clampX(fx0), x1 = clampX(fx0 + 1), y0 = clampY(fy0), y1 = clampY(fy0 + 1);
  auto at = [&](int tx, int ty) { return static_cast<size_t>(ty) * width + tx; };
  return {{at(x0, y0), at(x1, y0), at(x0, y1), at(x1, y1)},
          {(1 - ax) * (1 - ay), ax * (1 - ay), (1 - ax) * ay, ax * ay}};
}

} // namespace nx
