#pragma once
// A small log-log line plot rendered to RGB pixels (for benchmark reports).

#include "apps/plot_canvas.h"

namespace nx {

/// Renders series on log10 axes spanning all positive points (whole decades), with a grid,
/// axis labels and a legend. Returns width x height interleaved RGB bytes.
std::vector<uint8_t> renderLogLogPlot(const std::vector<PlotSeries>& series,
                                      const std::string& xLabel, const std::string& yLabel,
                                      const std::string& title, int width, int height);

} // namespace nx
