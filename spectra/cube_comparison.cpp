#include "spectra/cube_comparison.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/error.h"

namespace nx {
namespace {

constexpr double kRadToDeg = 57.29577951308232;

// The value below which a fraction q of the sorted values lie (linear between ranks).
double quantile(std::vector<double>& v, double q) {
  if (v.empty()) return std::numeric_limits<double>::quiet_NaN();
  std::sort(v.begin(), v.end());
  const double x = q * static_cast<double>(v.size() - 1);
  const size_t i = static_cast<size_t>(x);
  const double f = x - static_cast<double>(i);
  return i + 1 < v.size() ? v[i] * (1 - f) + v[i + 1] * f : v[i];
}

// The scale factors of `fit` over the used pixels p with take(p): least squares of capture
// against render, the render's noise taken out of the regressor's sum of squares when its
// variances are known (E[r^2] = mu^2 + var r: the plain fit's scale is low by about the
// render's relative variance; two renders of one scene at 16 and 64 spp were fitted 0.85-0.97).
template <class Take>
std::vector<double> bandScales(const ComparisonInputs& in, const std::vector<uint8_t>& used,
                               ScaleFit fit, Take&& take) {
  const size_t nb = static_cast<size_t>(in.bands);
  const size_t np = static_cast<size_t>(in.width) * static_cast<size_t>(in.height);
  std::vector<double> scale(nb, 1.0);
  if (fit == ScaleFit::None) return scale;
  std::vector<double> cr(nb, 0.0), rr(nb, 0.0);
  for (size_t p = 0; p < np; ++p)
    if (used[p] && take(p))
      for (size_t b = 0; b < nb; ++b) {
        const double r = in.render[p * nb + b], c = in.capture[p * nb + b];
        cr[b] += c * r;
        rr[b] += r * r - (in.renderVariance ? in.renderVariance[p * nb + b] : 0.0);
      }
  if (fit == ScaleFit::Global) {
    double scr = 0, srr = 0;
    for (size_t b = 0; b < nb; ++b) scr += cr[b], srr += rr[b];
    if (!(srr > 0)) throw Error("cannot fit a scale: the render is zero over the compared pixels");
    std::fill(scale.begin(), scale.end(), scr / srr);
  } else {
    for (size_t b = 0; b < nb; ++b) {
      if (!(rr[b] > 0))
        throw Error("cannot fit a scale for band " + numberText(in.wavelengthNm[b]) +
                    " nm: the render is zero there over the compared pixels");
      scale[b] = cr[b] / rr[b];
    }
  }
  return scale;
}

} // namespace

ComparisonReport compareCubes(const ComparisonInputs& in, ScaleFit fit) {
  const size_t np = static_cast<size_t>(in.width) * static_cast<size_t>(in.height);
  const size_t nb = static_cast<size_t>(in.bands);
  // The compared pixels: the union of the regions (all pixels without regions).
  std::vector<uint8_t> used(np, in.regions.empty() ? 1 : 0);
  for (const ComparisonRegion& r : in.regions)
    for (size_t p = 0; p < np; ++p)
      if (r.mask[p]) used[p] = 1;
  ComparisonReport rep;
  rep.fit = fit;
  if (!in.excluded.empty())
    for (size_t p = 0; p < np; ++p)
      if (in.excluded[p] && used[p]) used[p] = 0, ++rep.excludedPixels;
  for (size_t p = 0; p < np; ++p) rep.pixels += used[p];
  if (rep.pixels == 0)
    throw Error("expected at least one pixel to compare, found none in the regions");
  for (size_t p = 0; p < np; ++p) {
    if (!used[p]) continue;
    for (size_t b = 0; b < nb; ++b) {
      const float r = in.render[p * nb + b], c = in.capture[p * nb + b];
      if (!std::isfinite(r) || !std::isfinite(c))
        throw Error(
            std::string("expected finite values in the compared pixels, found ") +
            (std::isfinite(r) ? "capture" : "render") + " value " +
            numberText(std::isfinite(r) ? c : r) + " at pixel " +
            std::to_string(static_cast<long>(p % static_cast<size_t>(in.width)) + in.originX) +
            "," +
            std::to_string(static_cast<long>(p / static_cast<size_t>(in.width)) + in.originY) +
            " in band " + numberText(in.wavelengthNm[b]) + " nm (mask such pixels out)");
    }
  }

  // Scale factors (bandScales), and for a fitted scale its jackknife variance over
  // interleaved pixel groups: a scale fitted where the render is faint is uncertain, and that
  // uncertainty belongs in the z-scores (two renders of one scene read z = 15 at 420 nm with
  // --scale band, where the fitted factor was 7% off from noise alone).
  const std::vector<double> scale = bandScales(in, used, fit, [](size_t) { return true; });
  std::vector<double> biasJackknife(nb, -1.0); // the bias's jackknife variance; < 0: none
  if (fit != ScaleFit::None) {
    constexpr size_t kGroups = 16;
    // Per group: the sums of render and capture and the pixel count (leave-one-out = total -
    // group), and the scales fitted without it.
    std::vector<double> sumR(kGroups * nb, 0.0), sumC(kGroups * nb, 0.0), count(kGroups, 0.0);
    for (size_t p = 0; p < np; ++p)
      if (used[p]) {
        count[p % kGroups] += 1;
        for (size_t b = 0; b < nb; ++b) {
          sumR[(p % kGroups) * nb + b] += in.render[p * nb + b];
          sumC[(p % kGroups) * nb + b] += in.capture[p * nb + b];
        }
      }
    std::vector<std::vector<double>> parts;
    for (size_t g = 0; g < kGroups; ++g) {
      try {
        parts.push_back(bandScales(in, used, fit, [g](size_t p) { return p % kGroups != g; }));
      } catch (const Error&) { // a group holding all of a band's signal: no jackknife
        parts.clear();
        break;
      }
    }
    double pixels = 0;
    for (double c : count) pixels += c;
    for (size_t b = 0; b < nb && parts.size() == kGroups; ++b) {
      double totalR = 0, totalC = 0;
      for (size_t g = 0; g < kGroups; ++g) totalR += sumR[g * nb + b], totalC += sumC[g * nb + b];
      std::vector<double> biases;
      for (size_t g = 0; g < kGroups; ++g) {
        const double n = pixels - count[g];
        if (!(n > 0)) continue;
        biases.push_back((parts[g][b] * (totalR - sumR[g * nb + b]) - (totalC - sumC[g * nb + b])) /
                         n);
      }
      if (biases.size() < 2) continue;
      const double k = static_cast<double>(biases.size());
      double mean = 0, sum2 = 0;
      for (double x : biases) mean += x / k;
      for (double x : biases) sum2 += (x - mean) * (x - mean);
      biasJackknife[b] = (k - 1) / k * sum2;
    }
  }

  // Per band.
  const double n = static_cast<double>(rep.pixels);
  rep.bands.resize(nb);
  for (size_t b = 0; b < nb; ++b) {
    double sr = 0, sc = 0, sd = 0, sd2 = 0, maxC = 0, sVar = 0, sz2 = 0;
    long zPixels = 0;
    const double s = scale[b];
    for (size_t p = 0; p < np; ++p) {
      if (!used[p]) continue;
      const double r = s * in.render[p * nb + b], c = in.capture[p * nb + b], d = r - c;
      sr += r, sc += c, sd += d, sd2 += d * d;
      maxC = std::max(maxC, c);
      if (in.renderVariance) {
        const double v = s * s * in.renderVariance[p * nb + b] +
                         (in.captureVariance ? in.captureVariance[p * nb + b] : 0.0);
        sVar += v;
        sz2 += d * d;
        ++zPixels;
      }
    }
    BandFigures& f = rep.bands[b];
    f.wavelengthNm = in.wavelengthNm[b];
    f.scale = s;
    f.renderMean = sr / n;
    f.captureMean = sc / n;
    f.bias = sd / n;
    f.rmse = std::sqrt(sd2 / n);
    f.relativeRmse = f.rmse / f.renderMean;
    f.psnrDb =
        f.rmse > 0 ? 20 * std::log10(maxC / f.rmse) : std::numeric_limits<double>::infinity();
    const double nan = std::numeric_limits<double>::quiet_NaN();
    // The bias's error: from the pixels' variances for a given scale; for a fitted one, the
    // jackknife's (it holds the scale's own error and its covariance with the means).
    const double biasVariance = biasJackknife[b] >= 0 ? biasJackknife[b] : sVar / (n * n);
    f.zMean = in.renderVariance && sVar > 0 ? f.bias / std::sqrt(biasVariance) : nan;
    f.rmsZ = zPixels > 0 && sVar > 0 ? std::sqrt(sz2 / sVar) : nan;
  }

  // Per pixel: the spectral angle between scaled render and capture.
  rep.samMapDeg.assign(np, std::numeric_limits<float>::quiet_NaN());
  std::vector<double> angles;
  for (size_t p = 0; p < np; ++p) {
    if (!used[p]) continue;
    double rc = 0, rr = 0, cc = 0;
    for (size_t b = 0; b < nb; ++b) {
      const double r = scale[b] * in.render[p * nb + b], c = in.capture[p * nb + b];
      rc += r * c, rr += r * r, cc += c * c;
    }
    if (!(rr > 0 && cc > 0)) {
      ++rep.sam.undefinedPixels;
      continue;
    }
    const double a = std::acos(std::clamp(rc / std::sqrt(rr * cc), -1.0, 1.0)) * kRadToDeg;
    rep.samMapDeg[p] = static_cast<float>(a);
    angles.push_back(a);
  }
  rep.sam.pixels = static_cast<long>(angles.size());
  double sum = 0;
  for (double a : angles) sum += a, rep.sam.maxDeg = std::max(rep.sam.maxDeg, a);
  rep.sam.meanDeg = angles.empty() ? std::numeric_limits<double>::quiet_NaN()
                                   : sum / static_cast<double>(angles.size());
  rep.sam.medianDeg = quantile(angles, 0.5);
  rep.sam.p95Deg = quantile(angles, 0.95);

  // Per region.
  for (const ComparisonRegion& reg : in.regions) {
    RegionFigures f;
    f.name = reg.name;
    f.renderMean.assign(nb, 0.0);
    f.captureMean.assign(nb, 0.0);
    double samSum = 0;
    long samCount = 0;
    for (size_t p = 0; p < np; ++p) {
      if (!reg.mask[p] || !used[p]) continue;
      ++f.pixels;
      for (size_t b = 0; b < nb; ++b) {
        f.renderMean[b] += scale[b] * in.render[p * nb + b];
        f.captureMean[b] += in.capture[p * nb + b];
      }
      if (!std::isnan(rep.samMapDeg[p])) samSum += rep.samMapDeg[p], ++samCount;
    }
    for (size_t b = 0; b < nb && f.pixels > 0; ++b) {
      f.renderMean[b] /= static_cast<double>(f.pixels);
      f.captureMean[b] /= static_cast<double>(f.pixels);
    }
    f.samMeanDeg = samCount > 0 ? samSum / static_cast<double>(samCount)
                                : std::numeric_limits<double>::quiet_NaN();
    rep.regions.push_back(std::move(f));
  }
  return rep;
}

void addRegionColours(ComparisonReport& report, const std::vector<double>& wavelengthNm,
                      const ColourOptions& options) {
  auto spectrumOf = [&](const std::vector<double>& v) {
    return Spectrum(TabulatedSpectrum{wavelengthNm, v, true});
  };
  auto xyzOf = [&](const std::vector<double>& v) {
    return options.reflectance ? reflectanceToXyz(spectrumOf(v), options.illuminant)
                               : spectrumToXyz(spectrumOf(v));
  };
  Xyz white = spectrumToXyz(options.illuminant);
  if (options.reflectance) {
    white = {white.x / white.y, 1.0, white.z / white.y};
  } else {
    double yMax = 0;
    for (const RegionFigures& r : report.regions)
      yMax = std::max({yMax, xyzOf(r.renderMean).y, xyzOf(r.captureMean).y});
    if (!(yMax > 0)) yMax = 1;
    white = {white.x / white.y * yMax, yMax, white.z / white.y * yMax};
  }
  for (RegionFigures& r : report.regions) {
    if (r.pixels == 0) continue;
    r.renderLab = xyzToLab(xyzOf(r.renderMean), white);
    r.captureLab = xyzToLab(xyzOf(r.captureMean), white);
    r.deltaE2000 = deltaE2000(r.renderLab, r.captureLab);
  }
}

} // namespace nx
