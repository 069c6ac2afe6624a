#pragma once
// An RGB canvas with lines, dots, text (stb_easy_font) and image blits, for the plots the
// programs write (benchmark reports, nxcompare's figure).

#include <cstdint>
#include <string>
#include <vector>

namespace nx {

/// One series of (x, y) points, drawn as a polyline with dots.
struct PlotSeries {
  std::string label;
  std::vector<double> x, y;
  uint8_t r = 0, g = 0, b = 0;
  bool dashed = false;
};

/// width x height interleaved RGB bytes, white to start with.
struct Canvas {
  int w, h;
  std::vector<uint8_t> px;
  /// A white canvas.
  Canvas(int width, int height);
  /// One pixel (ignored outside the canvas).
  void set(int x, int y, uint8_t r, uint8_t g, uint8_t b);
  /// A line, solid or dashed.
  void line(double x0, double y0, double x1, double y1, uint8_t r, uint8_t g, uint8_t b,
            bool dashed = false);
  /// A filled dot of radius about 2.
  void dot(double x, double y, uint8_t r, uint8_t g, uint8_t b);
  /// Text with its top-left corner at (x, y), scaled 2x.
  void text(int x, int y, const std::string& s, uint8_t r = 0, uint8_t g = 0, uint8_t b = 0);
  /// Width of text() in pixels.
  static int textWidth(const std::string& s);
  /// Copies an RGB image (iw x ih) with its top-left corner at (x, y).
  void blit(int x, int y, int iw, int ih, const std::vector<uint8_t>& rgb);
};

} // namespace nx
