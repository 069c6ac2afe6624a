#pragma once
// Which image error a target aims at: the luminance's or the worst band's.

#include "core/error.h"
#include "integrators/film.h"

namespace nx {

/// An image error: the luminance's (Film::relativeRmsError), or the worst band's among the
/// bands whose centroid lies in [loNm, hiNm] (Film::worstBandRelativeRmsError).
struct ErrorMeasure {
  bool bands = false;
  double loNm = 0, hiNm = 1e9;
  /// Throws nx::Error unless the measure names something of a render with these bands: a
  /// band range holding no band's centroid would never be met (its error is infinite).
  void requireBandsIn(const Sensor& sensor) const {
    if (!bands) return;
    for (int b = 0; b < sensor.count(); ++b)
      if (sensor.centroid(b) >= loNm && sensor.centroid(b) <= hiNm) return;
    throw Error("--error-of: expected a range holding at least one band of the render (" +
                sensor.summary() + "), found bands:" + numberText(loNm) + "-" + numberText(hiNm));
  }
  /// The error of a film.
  double of(const Film& film) const {
    return bands ? film.worstBandRelativeRmsError(loNm, hiNm) : film.relativeRmsError();
  }
};

} // namespace nx
