#pragma once
// Rendering scene text in tests and comparing band means with expected values statistically.

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <string>

#include "integrators/renderer.h"
#include "integrators/scene_reader.h"
#include "support/statistics.h"

namespace nx {

/// A scene file's text from its settings, camera and objects.
inline std::string sceneText(const std::string& settings, const std::string& camera,
                             const std::string& body) {
  return "<scene><settings>" + settings + "</settings><camera>" + camera + "</camera>" + body +
         "</scene>";
}

/// Renders scene text (named t.scn in errors).
inline RenderOutput renderText(const std::string& text, const RenderOptions& options = {}) {
  const RenderScene scene = buildRenderScene(parseScene(text, "t.scn"));
  return render(scene, options);
}

/// Mean and standard error over pixels of band b (pixels are independent estimates).
inline test::RunningStats bandStats(const Film& film, int b,
                                    const std::function<bool(int, int)>& use = {}) {
  test::RunningStats s;
  for (int y = 0; y < film.height(); ++y)
    for (int x = 0; x < film.width(); ++x)
      if (!use || use(x, y)) s.add(film.bandMean(x, y, b));
  return s;
}

/// Every band's pixel mean equals expected(band) within the 5-sigma tail of a t-test over the
/// pixels (studentCritical: a standard error estimated from few pixels is itself uncertain;
/// with stratified lanes a pixel's band error takes few distinct values, so 16 pixels
/// misjudged it), and the test has power: the bands' relative standard errors, as an RMS over
/// the bands, are below `precision`. (One band's standard error from 64 pixels is itself
/// uncertain: measured 0.0054-0.0131 over six seeds where the bands' RMS was 0.0075, so a
/// per-band bound set the test failing by chance, not by a loss of power.)
inline void expectBands(const Film& film, const std::function<double(int)>& expected,
                        double precision, const std::function<bool(int, int)>& use = {},
                        const std::string& what = "") {
  double relativeSquares = 0;
  for (int b = 0; b < film.bands().count(); ++b) {
    const test::RunningStats s = bandStats(film, b, use);
    const double e = expected(b);
    ASSERT_GE(s.n, 2) << what << ": a standard error needs two pixels";
    ASSERT_GT(e, 0) << what << " band " << film.bands().centroid(b);
    const double critical = test::studentCritical(5, static_cast<int>(s.n));
    EXPECT_LT(std::abs(s.mean - e), critical * s.standardError() + 1e-6 * e)
        << what << " band " << film.bands().centroid(b) << ": mean " << s.mean << " expected " << e
        << " se " << s.standardError();
    relativeSquares += (s.standardError() / e) * (s.standardError() / e);
  }
  EXPECT_LT(std::sqrt(relativeSquares / film.bands().count()), precision)
      << what << ": the bands' standard errors (RMS, relative)";
}

/// Relative RMS error of a film's luminance against a reference film of the same image.
inline double relativeLuminanceError(const Film& film, const Film& ref) {
  double se = 0, mean = 0;
  for (int y = 0; y < film.height(); ++y)
    for (int x = 0; x < film.width(); ++x) {
      const double d = film.xyzMean(x, y).y - ref.xyzMean(x, y).y;
      se += d * d;
      mean += ref.xyzMean(x, y).y;
    }
  const double n = static_cast<double>(film.width()) * film.height();
  return std::sqrt(se / n) / (mean / n);
}

/// Per-pixel variance of one render of scene with options o in the band nearest `nm` (luminance
/// Y for nm = 0), averaged over the image: half the mean squared difference of two renders at
/// seeds seedA and seedB.
inline double seedPairVariance(const RenderScene& scene, RenderOptions o, double nm, uint32_t seedA,
                               uint32_t seedB) {
  o.seed = seedA;
  const RenderOutput a = render(scene, o);
  o.seed = seedB;
  const RenderOutput b = render(scene, o);
  int band = 0;
  for (int i = 0; i < a.film.bands().count(); ++i)
    if (std::abs(a.film.bands().centroid(i) - nm) < std::abs(a.film.bands().centroid(band) - nm))
      band = i;
  double v = 0;
  for (int y = 0; y < a.film.height(); ++y)
    for (int x = 0; x < a.film.width(); ++x) {
      const double d = nm > 0 ? a.film.bandMean(x, y, band) - b.film.bandMean(x, y, band)
                              : a.film.xyzMean(x, y).y - b.film.xyzMean(x, y).y;
      v += d * d / 2;
    }
  return v / (a.film.width() * a.film.height());
}

} // namespace nx
