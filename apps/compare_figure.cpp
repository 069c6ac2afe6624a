#include "apps/compare_figure.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "apps/linear_plot.h"
#include "io/preview_image.h"

namespace nx {

void writeComparisonFigure(const std::string& path, const ComparisonReport& rep, int width,
                           int height) {
  const int figW = 1200, panelH = 420;
  // The angle map scaled to at most 1160 x 600, keeping its aspect.
  const double mapScale = std::min(1160.0 / width, 600.0 / height);
  const int mapW = std::max(1, static_cast<int>(width * mapScale)),
            mapH = std::max(1, static_cast<int>(height * mapScale));
  Canvas c(figW, panelH + mapH + 90);

  std::vector<double> nm;
  for (const BandFigures& f : rep.bands) nm.push_back(f.wavelengthNm);
  PlotSeries rmse{"RMSE", nm, {}, 200, 30, 30}, bias{"bias", nm, {}, 30, 30, 200};
  for (const BandFigures& f : rep.bands) rmse.y.push_back(f.rmse), bias.y.push_back(f.bias);
  drawLinearPlot(c, 0, 0, figW / 2, panelH, {rmse, bias}, "wavelength (nm)", "render - capture",
                 "per-band error");

  const uint8_t palette[6][3] = {{200, 30, 30}, {30, 120, 30}, {30, 30, 200},
                                 {200, 120, 0}, {120, 0, 160}, {0, 140, 160}};
  std::vector<PlotSeries> spectra;
  if (rep.regions.empty()) {
    PlotSeries r{"render (all)", nm, {}, 200, 30, 30}, k{"capture", nm, {}, 200, 30, 30, true};
    for (const BandFigures& f : rep.bands)
      r.y.push_back(f.renderMean), k.y.push_back(f.captureMean);
    spectra = {r, k};
  }
  for (size_t i = 0; i < rep.regions.size() && i < 6; ++i) {
    const uint8_t* p = palette[i];
    spectra.push_back({rep.regions[i].name, nm, rep.regions[i].renderMean, p[0], p[1], p[2]});
    spectra.push_back({"", nm, rep.regions[i].captureMean, p[0], p[1], p[2], true});
  }
  drawLinearPlot(c, figW / 2, 0, figW / 2, panelH, spectra, "wavelength (nm)", "mean value",
                 "region spectra: render solid, capture dashed");

  std::vector<float> finite;
  for (float a : rep.samMapDeg)
    if (!std::isnan(a)) finite.push_back(a);
  std::sort(finite.begin(), finite.end());
  const double top =
      finite.empty() ? 1.0 : std::max(1e-6, double(finite[finite.size() * 99 / 100]));
  std::vector<uint8_t> map(static_cast<size_t>(mapW) * mapH * 3);
  for (int y = 0; y < mapH; ++y)
    for (int x = 0; x < mapW; ++x) {
      const int sx = std::min(width - 1, static_cast<int>(x / mapScale)),
                sy = std::min(height - 1, static_cast<int>(y / mapScale));
      const float a = rep.samMapDeg[static_cast<size_t>(sy) * width + sx];
      uint8_t* p = &map[(static_cast<size_t>(y) * mapW + x) * 3];
      if (std::isnan(a)) {
        p[0] = 60, p[1] = 90, p[2] = 200;
      } else {
        const auto g = static_cast<uint8_t>(std::lround(255 * std::min(1.0, a / top)));
        p[0] = p[1] = p[2] = g;
      }
    }
  char caption[160];
  std::snprintf(caption, sizeof caption,
                "spectral angle: black 0 deg, white %.3g deg (99th percentile) or more; blue: no "
                "angle (not compared, or all zero)",
                top);
  c.text(20, panelH + 10, caption);
  c.blit((figW - mapW) / 2, panelH + 40, mapW, mapH, map);
  writePreview(path, c.w, c.h, c.px);
}

} // namespace nx
