#pragma once
// The relighting tests' scene (a floor, a fluorescent sphere, lamps of light groups) and their
// checks: relightable renders, direct renders with another seed, bands compared by z-tests.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "integrators/relight_image.h"
#include "integrators/renderer.h"
#include "integrators/scene_reader.h"
#include "support/render_checks.h"
#include "support/statistics.h"

namespace nx {

// A floor, a fluorescent sphere and a sphere lamp of group "lamp" with the <emission> element
// `lamp`; a second lamp of group "fill" (emission element `fill`) when that is not empty.
inline std::string benchScene(const std::string& lamp, const std::string& fill = "",
                              int samples = 64, const std::string& bands = "400:700:20") {
  return "<scene><settings><xres>32</xres><yres>32</yres><mode>spectral_mcpt</mode><depth>4</"
         "depth><sampl>" +
         std::to_string(samples) + "</sampl><bands>" + bands +
         "</bands></settings><camera><position>0,1,-5</position><look_at>0,0.5,0</look_at><fov>"
         "40</fov></camera><plane><normal>0,1,0</normal><distance>0</distance><material>matte</"
         "material><reflectance>400:0.3, 700:0.8</reflectance></plane>"
         "<sphere><center>0,0.7,0</center><radius>0.7</radius><material>matte</material>"
         "<reflectance>0.5</reflectance><fluorescence><absorption>blue</absorption><stokes>100</"
         "stokes></fluorescence></sphere>"
         "<sphere group=\"lamp\"><center>-1.5,2.5,-1</center><radius>0.5</radius><material>matte"
         "</material><reflectance>0</reflectance>" +
         lamp + "</sphere>" +
         (fill.empty() ? ""
                       : "<sphere group=\"fill\"><center>1.8,1.5,-1.5</center><radius>0.3</"
                         "radius><material>matte</material><reflectance>0</reflectance>" +
                             fill + "</sphere>") +
         "</scene>";
}

// Smooth and red-heavy; an LED-like shape; black but for 430-470 nm.
inline const std::string kLampS1 = "<emission scale=\"2e-4\">blackbody:4000</emission>";
inline const std::string kLampS2 =
    "<emission scale=\"2e-4\">380:0.2, 450:3, 500:0.5, 560:2, 650:1, 800:0.1</emission>";
inline const std::string kNarrowLamp =
    "<emission scale=\"2e-4\">430:0, 440:5, 460:5, 470:0</emission>";

inline RenderScene relightableScene(const std::string& text) {
  SceneDesc d = parseScene(text, "t.scn");
  d.relightable = true;
  return buildRenderScene(d);
}

inline RenderOutput renderRelightable(const std::string& text, double stepNm = 5,
                                      const RenderOptions& base = {}) {
  const RenderScene scene = relightableScene(text);
  RenderOptions o = base;
  o.relightStepNm = stepNm;
  RenderOutput out = render(scene, o);
  EXPECT_EQ(out.stats.relightMissed, 0u);
  return out;
}

// Image mean and standard error (over pixels) of band b of an image.
inline test::RunningStats imageBand(const SpectralImage& img, int b) {
  test::RunningStats s;
  const int nb = img.bands.count();
  for (size_t i = 0; i < img.sampleCount.size(); ++i)
    s.add(img.radiance[i * static_cast<size_t>(nb) + static_cast<size_t>(b)]);
  return s;
}

// The values and variances of image `img`'s radiance (`layer` empty) or component layer.
inline std::pair<const std::vector<float>*, const std::vector<float>*>
layerOf(const SpectralImage& img, const std::string& layer) {
  if (layer.empty()) return {&img.radiance, &img.bandVariance};
  for (const ImageLayer& l : img.layers)
    if (l.name == layer) return {&l.values, &l.variances};
  ADD_FAILURE() << "no layer " << layer;
  return {&img.radiance, &img.bandVariance};
}

// Every band of `a` equals `b`'s (an independent render) within 5 standard errors of the
// mean pixel difference (pixels are independent estimates; the t critical value for their
// count), and within 5 standard errors from both images' own variance channels; the test has
// power: the standard errors, relative to the bands' means as an RMS over the bands, are below
// `power` (5%; one band's alone is too uncertain a measure of it: see expectBands). `layer`:
// a component layer of both instead of the radiance; bands where `b`'s layer is below 1% of its
// brightest band are compared by the z-tests alone (a component dark there).
inline void expectSameBands(const SpectralImage& a, const SpectralImage& b, const std::string& what,
                            const std::string& layer = "", double power = 0.05) {
  const size_t nb = static_cast<size_t>(a.bands.count());
  const double pixels = static_cast<double>(a.sampleCount.size());
  const double critical = test::studentCritical(5, static_cast<int>(a.sampleCount.size()));
  const auto [av, avar] = layerOf(a, layer);
  const auto [bv, bvar] = layerOf(b, layer);
  std::vector<test::RunningStats> d(nb), y(nb);
  std::vector<double> variances(nb, 0.0); // per band, both images' variances of pixel means
  for (size_t k = 0; k < nb; ++k)
    for (size_t i = 0; i < a.sampleCount.size(); ++i) {
      d[k].add((*av)[i * nb + k] - (*bv)[i * nb + k]);
      y[k].add((*bv)[i * nb + k]);
      variances[k] += (*avar)[i * nb + k] + (*bvar)[i * nb + k];
    }
  double brightest = 0, relativeSquares = 0;
  int counted = 0;
  for (size_t k = 0; k < nb; ++k) brightest = std::max(brightest, y[k].mean);
  ASSERT_GT(brightest, 0.0) << what;
  for (size_t k = 0; k < nb; ++k) {
    const double band = a.bands.centroid(static_cast<int>(k));
    EXPECT_LE(std::abs(d[k].mean), 5 * std::sqrt(variances[k]) / pixels)
        << what << " band " << band << " (z from the variance channels)";
    EXPECT_LE(std::abs(d[k].mean), critical * d[k].standardError())
        << what << " band " << band << ": difference " << d[k].mean << " se "
        << d[k].standardError() << " of " << y[k].mean;
    if (y[k].mean < 0.01 * brightest) continue;
    relativeSquares += (d[k].standardError() / y[k].mean) * (d[k].standardError() / y[k].mean);
    ++counted;
  }
  ASSERT_GT(counted, 0) << what;
  EXPECT_LT(std::sqrt(relativeSquares / counted), power)
      << what << ": the bands' standard errors (RMS, relative)";
}

// A direct render of scene text with another seed than the relightable one.
inline SpectralImage directRender(const std::string& text) {
  RenderOptions o;
  o.seed = 7;
  return toSpectralImage(renderText(text, o).film);
}

// The mean variance channel of band b over the image.
inline double meanVariance(const SpectralImage& img, int b) {
  double sum = 0;
  const int nb = img.bands.count();
  for (size_t i = 0; i < img.sampleCount.size(); ++i)
    sum += img.bandVariance[i * static_cast<size_t>(nb) + static_cast<size_t>(b)];
  return sum / static_cast<double>(img.sampleCount.size());
}

// The spectrum an <emission> element is, as written (without its scale).
inline Spectrum writtenSpectrum(const std::string& element) {
  const RenderScene s = relightableScene(benchScene(element));
  return s.relight.ofSource[s.lightGroups.sourceOfEmission.back()];
}

inline GroupSpectrum binned(const SpectralImage& img, const std::string& group,
                            const std::string& element) {
  std::vector<std::string> warnings;
  GroupSpectrum g =
      groupSpectrum(img, group, writtenSpectrum(element), 300, 1100, element, warnings);
  EXPECT_TRUE(warnings.empty()) << (warnings.empty() ? "" : warnings[0]);
  return g;
}

} // namespace nx
