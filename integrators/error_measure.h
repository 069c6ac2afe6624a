#pragma once
// Which image error a target aims at: the luminance's or the worst band's.

#include "integrators/film.h"

namespace nx {

/// An image error: the luminance's (Film::relativeRmsError), or the worst band's among the
/// bands whose centroid lies in [loNm, hiNm] (Film::worstBandRelativeRmsError).
struct ErrorMeasure {
  bool bands = false;
  double loNm = 0, hiNm = 1e9;
  /// The error of a film.
  double of(const Film& film) const {
    return bands ? film.worstBandRelativeRmsError(loNm, hiNm) : film.relativeRmsError();
  }
};

} // namespace nx
