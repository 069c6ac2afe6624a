#include "apps/linear_plot.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace nx {
namespace {

// A tick step of 1, 2 or 5 times a power of ten giving about `count` intervals over span.
double niceStep(double span, int count) {
  const double raw = span / count, p = std::pow(10.0, std::floor(std::log10(raw)));
  for (double m : {1.0, 2.0, 5.0})
    if (m * p >= raw) return m * p;
  return 10 * p;
}

std::string tickText(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", std::abs(v) < 1e-12 ? 0.0 : v);
  return buf;
}

} // namespace

void drawLinearPlot(Canvas& c, int x0, int y0, int width, int height,
                    const std::vector<PlotSeries>& series, const std::string& xLabel,
                    const std::string& yLabel, const std::string& title) {
  double xMin = INFINITY, xMax = -INFINITY, yMin = INFINITY, yMax = -INFINITY;
  for (const auto& s : series)
    for (size_t i = 0; i < s.x.size(); ++i)
      if (std::isfinite(s.x[i]) && std::isfinite(s.y[i])) {
        xMin = std::min(xMin, s.x[i]), xMax = std::max(xMax, s.x[i]);
        yMin = std::min(yMin, s.y[i]), yMax = std::max(yMax, s.y[i]);
      }
  if (!(xMin <= xMax)) xMin = 0, xMax = 1, yMin = 0, yMax = 1;
  if (xMax == xMin) xMin -= 1, xMax += 1;
  if (yMax == yMin)
    yMin -= 0.5 * std::max(1e-12, std::abs(yMin)), yMax += 0.5 * std::max(1e-12, std::abs(yMax));
  const double xs = niceStep(xMax - xMin, 8), ys = niceStep(yMax - yMin, 6);
  xMin = std::floor(xMin / xs) * xs, xMax = std::ceil(xMax / xs) * xs;
  yMin = std::floor(yMin / ys) * ys, yMax = std::ceil(yMax / ys) * ys;
  const double left = x0 + 100, right = x0 + width - 20, top = y0 + 44, bottom = y0 + height - 60;
  auto X = [&](double v) { return left + (v - xMin) / (xMax - xMin) * (right - left); };
  auto Y = [&](double v) { return bottom - (v - yMin) / (yMax - yMin) * (bottom - top); };
  for (double v = xMin; v <= xMax + 0.5 * xs; v += xs) {
    c.line(X(v), top, X(v), bottom, 225, 225, 225);
    const std::string s = tickText(v);
    c.text(static_cast<int>(X(v)) - Canvas::textWidth(s) / 2, static_cast<int>(bottom) + 8, s);
  }
  for (double v = yMin; v <= yMax + 0.5 * ys; v += ys) {
    c.line(left, Y(v), right, Y(v), 225, 225, 225);
    const std::string s = tickText(v);
    c.text(static_cast<int>(left) - Canvas::textWidth(s) - 8, static_cast<int>(Y(v)) - 7, s);
  }
  c.line(left, bottom, right, bottom, 0, 0, 0);
  c.line(left, top, left, bottom, 0, 0, 0);
  c.text(static_cast<int>((left + right) / 2) - Canvas::textWidth(xLabel) / 2, y0 + height - 28,
         xLabel);
  c.text(static_cast<int>((left + right) / 2) - Canvas::textWidth(title) / 2, y0 + 2, title);
  c.text(x0 + 8, y0 + 20, yLabel);
  int legendY = static_cast<int>(top) + 10;
  for (const auto& s : series) {
    for (size_t i = 0; i + 1 < s.x.size(); ++i)
      if (std::isfinite(s.y[i]) && std::isfinite(s.y[i + 1]))
        c.line(X(s.x[i]), Y(s.y[i]), X(s.x[i + 1]), Y(s.y[i + 1]), s.r, s.g, s.b, s.dashed);
    if (s.label.empty()) continue;
    c.line(right - 260, legendY + 6, right - 230, legendY + 6, s.r, s.g, s.b, s.dashed);
    c.text(static_cast<int>(right) - 222, legendY, s.label, s.r, s.g, s.b);
    legendY += 22;
  }
}

} // namespace nx
