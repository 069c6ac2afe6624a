#pragma once
// A spectral environment light: radiance arriving from infinitely far away in every direction,
// read from a spectral EXR in the project's own layout (docs/output.md) as a latitude-longitude
// map, importance-sampled by its texels' radiance times sin(theta) (piecewise constant:
// marginal over rows, then conditional over the row; pbrt-v4's PiecewiseConstant2D) and
// combined with BSDF sampling by MIS. Texel (i, j) of a W x H map covers phi in
// 2 pi [i, i + 1) / W and theta in pi [j, j + 1) / H (row 0 at the zenith), the direction
// (sin theta cos phi, cos theta, sin theta sin phi): +y is up.

#include "core/cell_index.h"
#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include "core/error.h"
#include "core/memory.h"
#include "core/text_table.h"
#include "integrators/lights/light_kind.h"

namespace nx {

/// An environment light.
struct EnvironmentLight {
  int width = 0, height = 0;
  std::vector<double> bandNm; ///< the map's band centroids, increasing
  /// What its bands cover: from the first band's lower edge to the last's upper one (a band's
  /// value holds over its support, not from its centroid); beyond, 0 or held (extrapolate).
  double supportLoNm = 0, supportHiNm = 0;
  std::shared_ptr<const std::vector<float>> texels;  ///< [texel][band] radiance (times its scale)
  std::shared_ptr<const std::vector<double>> rowCdf; ///< [height + 1] marginal over rows
  std::shared_ptr<const std::vector<double>> columnCdf; ///< [height][width + 1] per row
  std::shared_ptr<const std::vector<float>> texelPdf;   ///< [texel] density over (u, v) in [0,1]^2
  double integral = 0; ///< of L over directions and the traced range (W m^-2 nm ... per sr)

  static constexpr bool kInfinite = true;
  static constexpr const char* kName = "environment";
  static constexpr const char* kDoc =
      "a spectral environment map (latitude-longitude spectral EXR, +y up): radiance from "
      "infinitely far in every direction, importance-sampled";
  /// Its parameters.
  static std::span<const LightParameter> parameters() {
    static const LightParameter p[] = {
        {{"file", ParamType::File, "-", nullptr,
          "a spectral EXR in the project's layout: radiance per band, W m^-2 sr^-1 nm^-1",
          "sky.exr"},
         "",
         true},
        {{"scale", ParamType::Number, "1", &kPositiveScaleRange, "the factor on its radiance", "1"},
         "1"},
        {{"extrapolate", ParamType::Name, "-", nullptr,
          "beyond the wavelengths its bands cover: zero, or hold the edge bands' radiance "
          "(unset: zero, and a render tracing beyond warns)",
          "hold"},
         ""},
    };
    return p;
  }

  /// Builds it: the map read, checked (finite, non-negative, within the emission limit) and
  /// its sampling tables made.
  static EnvironmentLight build(const ParameterSet& p, const LightInputs& in) {
    const std::string& file = *p.get<std::string>("file");
    const SourceLocation& where = p.locOf("file", in.loc);
    const std::shared_ptr<const SpectralImage> img = in.spectralImage(file, where);
    // A reflective file (T.<wavelength> channels: reflectances, Fichet et al. 2021) holds no
    // radiance: its values are not W m^-2 sr^-1 nm^-1.
    if (const auto it = img->attributes.find("nxrender.spectralChannels");
        it != img->attributes.end() && it->second == "T")
      throw Error(where.str() + ": " + file +
                  ": expected an emissive spectral EXR (S0.<wavelength> channels: radiance), "
                  "found a reflective one (T.<wavelength> channels: reflectances, for a "
                  "<reflectance texture=\"...\">)");
    const double scale = p.number("scale").value_or(1.0);
    EnvironmentLight e;
    e.width = img->width, e.height = img->height;
    const int nb = img->bands.count();
    std::vector<int> order(static_cast<size_t>(nb));
    for (int b = 0; b < nb; ++b) order[static_cast<size_t>(b)] = b;
    std::sort(order.begin(), order.end(),
              [&](int a, int b) { return img->bands.centroid(a) < img->bands.centroid(b); });
    for (int b : order) e.bandNm.push_back(img->bands.centroid(b));
    // Every band's radiance holds over its support (a map written with bands 400:700:10
    // covers 395-705 nm; it rendered its edge bands at half).
    e.supportLoNm = std::min(e.bandNm.front(), img->bands.minNm());
    e.supportHiNm = std::max(e.bandNm.back(), img->bands.maxNm());
    const std::string* extrapolate = p.get<std::string>("extrapolate");
    if (extrapolate && *extrapolate != "zero" && *extrapolate != "hold")
      throw Error(p.locOf("extrapolate", in.loc).str() +
                  ": expected <extrapolate> zero or hold, found '" + *extrapolate + "'");
    if (extrapolate && *extrapolate == "hold") {
      e.supportLoNm = -INFINITY;
      e.supportHiNm = INFINITY;
    }
    if (!extrapolate)
      in.tabulated(where, file, e.supportLoNm, e.supportHiNm,
                   "write <extrapolate>zero</extrapolate> or <extrapolate>hold</extrapolate> in "
                   "the <light>");
    const size_t n = static_cast<size_t>(e.width) * static_cast<size_t>(e.height);
    // Its tables beside the image just read: radiance per band, weights, both CDFs, the pdf.
    requireMemory(static_cast<double>(n) * (4.0 * nb + 8 + 8 + 4), where.str(),
                  "an environment map",
                  std::to_string(e.width) + "x" + std::to_string(e.height) + " texels with " +
                      std::to_string(nb) + " bands");
    auto texels = std::make_shared<std::vector<float>>(n * static_cast<size_t>(nb));
    std::vector<double> weight(n, 0.0);
    for (size_t t = 0; t < n; ++t)
      for (size_t k = 0; k < order.size(); ++k) {
        const double v = scale * img->radiance[t * static_cast<size_t>(nb) + order[k]];
        if (!(v >= 0 && v <= kMaxEmission))
          throw Error(where.str() + ": " + file + ": expected radiance within [0, " +
                      numberText(kMaxEmission) + "] (after its scale), found " + numberText(v) +
                      " at texel " + std::to_string(t % e.width) + "," +
                      std::to_string(t / e.width) + " in band " + numberText(e.bandNm[k]) + " nm");
        (*texels)[t * order.size() + k] = static_cast<float>(v);
        weight[t] += v;
      }
    // Sampling weights: a texel's summed radiance times sin(theta) at its centre (the
    // solid angle it covers); every texel that emits keeps a chance.
    auto rowCdf = std::make_shared<std::vector<double>>(static_cast<size_t>(e.height) + 1, 0.0);
    auto columnCdf = std::make_shared<std::vector<double>>(
        static_cast<size_t>(e.height) * (static_cast<size_t>(e.width) + 1), 0.0);
    auto texelPdf = std::make_shared<std::vector<float>>(n, 0.0f);
    std::vector<double> rowSum(static_cast<size_t>(e.height), 0.0);
    double total = 0;
    for (int j = 0; j < e.height; ++j) {
      const double sinTheta = std::sin(kPi * (j + 0.5) / e.height);
      double* cdf = &(*columnCdf)[static_cast<size_t>(j) * (e.width + 1)];
      for (int i = 0; i < e.width; ++i) {
        const size_t t = static_cast<size_t>(j) * e.width + i;
        const double w = weight[t] * sinTheta;
        cdf[i + 1] = cdf[i] + w;
        e.integral += weight[t] / nb * (2 * kPi / e.width) *
                      (std::cos(kPi * j / e.height) - std::cos(kPi * (j + 1) / e.height));
      }
      rowSum[static_cast<size_t>(j)] = cdf[e.width];
      total += cdf[e.width];
      (*rowCdf)[static_cast<size_t>(j) + 1] = total;
    }
    e.integral *= std::min(e.supportHiNm, kTraceMaxNm) - std::max(e.supportLoNm, kTraceMinNm);
    if (!(total > 0))
      throw Error(where.str() + ": expected an environment map that emits somewhere, found " +
                  file + " black everywhere");
    for (int j = 0; j < e.height; ++j)
      for (int i = 0; i < e.width; ++i) {
        const size_t t = static_cast<size_t>(j) * e.width + i;
        const double sinTheta = std::sin(kPi * (j + 0.5) / e.height);
        (*texelPdf)[t] = static_cast<float>(weight[t] * sinTheta / total * static_cast<double>(n));
      }
    e.texels = texels;
    e.rowCdf = rowCdf;
    e.columnCdf = columnCdf;
    e.texelPdf = texelPdf;
    return e;
  }

  /// The texel a direction falls in.
  size_t texelOf(const Vec3& d) const {
    // theta from both components: accurate at the poles, where d.y rounds to 1.
    const float theta = std::atan2(std::sqrt(d.x * d.x + d.z * d.z), d.y);
    float phi = std::atan2(d.z, d.x);
    if (phi < 0) phi += static_cast<float>(2 * kPi);
    // NaN and out-of-range angles (a NaN direction) land in an edge texel, never outside.
    const int i = cellIndex(phi * static_cast<float>(width / (2 * kPi)), width);
    const int j = cellIndex(theta * static_cast<float>(height / kPi), height);
    return static_cast<size_t>(j) * width + static_cast<size_t>(i);
  }
  /// Radiance arriving from direction d (from the sky towards the scene: d points to the sky).
  SampledSpectrum radiance(const Vec3& d, const SampledWavelengths& lambda) const {
    const float* v = &(*texels)[texelOf(d) * bandNm.size()];
    SampledSpectrum out;
    for (int k = 0; k < kLanes; ++k) {
      const double nm = lambda.lambda[k];
      if (!(nm >= supportLoNm && nm <= supportHiNm)) continue; // 0 beyond its bands (warned)
      // Between the edge bands' centroids and their edges: the edge band's value.
      if (nm <= bandNm.front() || nm >= bandNm.back()) {
        out[k] = v[nm <= bandNm.front() ? 0 : bandNm.size() - 1];
        continue;
      }
      const size_t hi = std::min(
          bandNm.size() - 1,
          static_cast<size_t>(std::upper_bound(bandNm.begin(), bandNm.end(), nm) - bandNm.begin()));
      const size_t lo = hi == 0 ? 0 : hi - 1;
      const double t = hi == lo ? 0.0 : (nm - bandNm[lo]) / (bandNm[hi] - bandNm[lo]);
      out[k] = static_cast<float>((1 - t) * v[lo] + t * v[hi]);
    }
    return out;
  }
  /// Solid-angle density of sample() returning direction d.
  float pdf(const Vec3& d) const {
    const float sinTheta = std::sqrt(d.x * d.x + d.z * d.z); // not 1 - y^2 (0 near the poles)
    if (!(sinTheta > 0)) return 0;
    return (*texelPdf)[texelOf(d)] / static_cast<float>(2 * kPi * kPi * sinTheta);
  }
  /// Where Local light selection weighs it from (it is everywhere alike).
  Vec3 center() const { return Vec3(0, 0, 0); }
  /// Its mean radiance over directions, integrated over the traced range.
  double tracedPeak() const { return integral / (4 * kPi); }
  /// The power it sends into a sphere of radius r around the scene: pi r^2 times the
  /// integral of L over directions (the uniform background's 4 pi^2 r^2 L for a constant map).
  double power(double sceneRadius = 1) const { return kPi * sceneRadius * sceneRadius * integral; }
  /// A direction drawn by the map's radiance: a row by the marginal, a column by the row's
  /// conditional, uniform within the texel (u, v), then to the sphere.
  bool sample(const Vec3&, Sample2 u, const SampledWavelengths& lambda, LightSample& out) const {
    const std::vector<double>& rows = *rowCdf;
    const double total = rows.back();
    const double ty = u.u * total;
    const int j = std::clamp(
        static_cast<int>(std::upper_bound(rows.begin(), rows.end(), ty) - rows.begin()) - 1, 0,
        height - 1);
    const double* cdf = &(*columnCdf)[static_cast<size_t>(j) * (width + 1)];
    const double rowTotal = cdf[width];
    if (!(rowTotal > 0)) return false;
    const double fy = std::clamp((ty - rows[j]) / (rows[j + 1] - rows[j]), 0.0, 1.0);
    const double tx = u.v * rowTotal;
    const int i = std::clamp(static_cast<int>(std::upper_bound(cdf, cdf + width + 1, tx) - cdf) - 1,
                             0, width - 1);
    const double fx = std::clamp((tx - cdf[i]) / (cdf[i + 1] - cdf[i]), 0.0, 1.0);
    const double phi = 2 * kPi * (i + fx) / width, theta = kPi * (j + fy) / height;
    const double s = std::sin(theta);
    out.wi = Vec3(static_cast<float>(s * std::cos(phi)), static_cast<float>(std::cos(theta)),
                  static_cast<float>(s * std::sin(phi)));
    out.pdf = pdf(out.wi);
    if (!(out.pdf > 0) || !std::isfinite(out.pdf)) return false;
    out.distance = INFINITY;
    out.infinite = true;
    out.delta = false;
    out.radiance = radiance(out.wi, lambda);
    return true;
  }
};

} // namespace nx
