#include "apps/plot_canvas.h"

#include <algorithm>
#include <cmath>

#define STB_EASY_FONT_IMPLEMENTATION
#include <stb/stb_easy_font.h>

namespace nx {

Canvas::Canvas(int width, int height)
    : w(width), h(height), px(static_cast<size_t>(width) * height * 3, 255) {}

void Canvas::set(int x, int y, uint8_t r, uint8_t g, uint8_t b) {
  if (x < 0 || y < 0 || x >= w || y >= h) return;
  uint8_t* p = &px[(static_cast<size_t>(y) * w + x) * 3];
  p[0] = r, p[1] = g, p[2] = b;
}

void Canvas::line(double x0, double y0, double x1, double y1, uint8_t r, uint8_t g, uint8_t b,
                  bool dashed) {
  const int steps = static_cast<int>(std::max(std::abs(x1 - x0), std::abs(y1 - y0))) + 1;
  for (int i = 0; i <= steps; ++i) {
    if (dashed && (i / 6) % 2) continue;
    const double t = static_cast<double>(i) / steps;
    set(static_cast<int>(std::lround(x0 + (x1 - x0) * t)),
        static_cast<int>(std::lround(y0 + (y1 - y0) * t)), r, g, b);
  }
}

void Canvas::dot(double x, double y, uint8_t r, uint8_t g, uint8_t b) {
  for (int dy = -2; dy <= 2; ++dy)
    for (int dx = -2; dx <= 2; ++dx)
      if (dx * dx + dy * dy <= 5)
        set(static_cast<int>(std::lround(x)) + dx, static_cast<int>(std::lround(y)) + dy, r, g, b);
}

void Canvas::text(int x, int y, const std::string& s, uint8_t r, uint8_t g, uint8_t b) {
  static thread_local char buffer[99999];
  const int quads =
      stb_easy_font_print(0, 0, const_cast<char*>(s.c_str()), nullptr, buffer, sizeof buffer);
  for (int q = 0; q < quads; ++q) {
    const float* v = reinterpret_cast<const float*>(buffer + q * 64); // 4 vertices of 16 bytes
    const int qx0 = static_cast<int>(v[0] * 2), qy0 = static_cast<int>(v[1] * 2);
    const int qx1 = static_cast<int>(v[8] * 2), qy1 = static_cast<int>(v[9] * 2);
    for (int yy = qy0; yy < qy1; ++yy)
      for (int xx = qx0; xx < qx1; ++xx) set(x + xx, y + yy, r, g, b);
  }
}

int Canvas::textWidth(const std::string& s) {
  return 2 * stb_easy_font_width(const_cast<char*>(s.c_str()));
}

void Canvas::blit(int x, int y, int iw, int ih, const std::vector<uint8_t>& rgb) {
  for (int j = 0; j < ih; ++j)
    for (int i = 0; i < iw; ++i) {
      const uint8_t* p = &rgb[(static_cast<size_t>(j) * iw + i) * 3];
      set(x + i, y + j, p[0], p[1], p[2]);
    }
}

} // namespace nx
