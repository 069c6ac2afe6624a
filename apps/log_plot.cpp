#include "apps/log_plot.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "apps/plot_canvas.h"

namespace nx {
namespace {

std::string decade(int e) {
  char buf[32];
  if (e >= -3 && e <= 4)
    std::snprintf(buf, sizeof buf, "%g", std::pow(10.0, e));
  else
    std::snprintf(buf, sizeof buf, "1e%d", e);
  return buf;
}

} // namespace

std::vector<uint8_t> renderLogLogPlot(const std::vector<PlotSeries>& series,
                                      const std::string& xLabel, const std::string& yLabel,
                                      const std::string& title, int width, int height) {
  double xMin = INFINITY, xMax = -INFINITY, yMin = INFINITY, yMax = -INFINITY;
  for (const auto& s : series)
    for (size_t i = 0; i < s.x.size(); ++i)
      if (s.x[i] > 0 && s.y[i] > 0) {
        xMin = std::min(xMin, s.x[i]), xMax = std::max(xMax, s.x[i]);
        yMin = std::min(yMin, s.y[i]), yMax = std::max(yMax, s.y[i]);
      }
  if (!(xMin <= xMax)) xMin = 1, xMax = 10, yMin = 1, yMax = 10;
  const int ex0 = static_cast<int>(std::floor(std::log10(xMin))),
            ex1 = std::max(ex0 + 1, static_cast<int>(std::ceil(std::log10(xMax))));
  const int ey0 = static_cast<int>(std::floor(std::log10(yMin))),
            ey1 = std::max(ey0 + 1, static_cast<int>(std::ceil(std::log10(yMax))));
  Canvas c(width, height);
  const double left = 90, right = width - 20, top = 40, bottom = height - 60;
  auto X = [&](double x) { return left + (std::log10(x) - ex0) / (ex1 - ex0) * (right - left); };
  auto Y = [&](double y) { return bottom - (std::log10(y) - ey0) / (ey1 - ey0) * (bottom - top); };
  for (int e = ex0; e <= ex1; ++e) {
    c.line(X(std::pow(10.0, e)), top, X(std::pow(10.0, e)), bottom, 215, 215, 215);
    const std::string s = decade(e);
    c.text(static_cast<int>(X(std::pow(10.0, e))) - Canvas::textWidth(s) / 2,
           static_cast<int>(bottom) + 8, s);
  }
  for (int e = ey0; e <= ey1; ++e) {
    c.line(left, Y(std::pow(10.0, e)), right, Y(std::pow(10.0, e)), 215, 215, 215);
    const std::string s = decade(e);
    c.text(static_cast<int>(left) - Canvas::textWidth(s) - 8,
           static_cast<int>(Y(std::pow(10.0, e))) - 7, s);
  }
  c.line(left, bottom, right, bottom, 0, 0, 0);
  c.line(left, top, left, bottom, 0, 0, 0);
  c.text(static_cast<int>((left + right) / 2) - Canvas::textWidth(xLabel) / 2, height - 28, xLabel);
  c.text(8, 12, yLabel);
  c.text(static_cast<int>((left + right) / 2) - Canvas::textWidth(title) / 2, 12, title);
  int legendY = static_cast<int>(top) + 10;
  for (const auto& s : series) {
    for (size_t i = 0; i + 1 < s.x.size(); ++i)
      if (s.x[i] > 0 && s.y[i] > 0 && s.x[i + 1] > 0 && s.y[i + 1] > 0)
        c.line(X(s.x[i]), Y(s.y[i]), X(s.x[i + 1]), Y(s.y[i + 1]), s.r, s.g, s.b, s.dashed);
    if (!s.dashed)
      for (size_t i = 0; i < s.x.size(); ++i)
        if (s.x[i] > 0 && s.y[i] > 0) c.dot(X(s.x[i]), Y(s.y[i]), s.r, s.g, s.b);
    c.line(right - 230, legendY + 6, right - 200, legendY + 6, s.r, s.g, s.b, s.dashed);
    c.text(static_cast<int>(right) - 192, legendY, s.label, s.r, s.g, s.b);
    legendY += 22;
  }
  return c.px;
}

} // namespace nx
