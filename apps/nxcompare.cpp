// nxcompare: compares a render with a capture (or two cubes) band by band.
//
//   nxcompare RENDER CAPTURE [--srf FILE.csv] [--capture-wavelengths L] [--capture-fwhm F]
//             [--rect X,Y,W,H]... [--mask MASK.png] [--labels] [--scale none|global|band]
//             [--crop X,Y,W,H] [--offset DX,DY] [--black-level DN] [--exclude-above V]
//             [--skip-nonfinite]
//             [--csv OUT.csv] [--region-csv OUT.csv] [--sam-map MAP.tif]
//             [--plot FIG.png] [--colour radiance|reflectance] [--illuminant NAME]
//             [--max-sam DEG] [--max-relative-rmse R]
//
// Either side may be a spectral EXR, an ENVI cube or a multi-band TIFF. The render's bands
// are resampled through the capture's (Gaussians from its fwhm, or measured responses from an
// SRF CSV) unless both have the same bands. Prints per-band figures and spectral-angle
// statistics; exit status 0 within the thresholds, 1 beyond them, 2 on errors.
// See docs/compare.md.

#include <CLI/CLI.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <map>
#include <optional>
#include <sstream>

#include "apps/command_line.h"
#include "apps/compare_figure.h"
#include "core/error.h"
#include "core/file_text.h"
#include "core/input_files.h"
#include "core/text_table.h"
#include "io/atomic_file.h"
#include "io/float_tiff.h"
#include "io/preview_image.h"
#include "io/spectral_cube.h"
#include "io/srgb_image.h"
#include "spectra/band_resampling.h"
#include "spectra/cube_comparison.h"
#include "spectra/illuminants.h"

namespace {

using nx::Error;

// "a,b,c" or "START:END:STEP" as numbers.
std::vector<double> numberList(const std::string& text, const std::string& option) {
  std::vector<double> out;
  if (text.find(':') != std::string::npos) {
    std::vector<double> p;
    std::stringstream ss(text);
    std::string cell;
    while (std::getline(ss, cell, ':')) p.push_back(nx::parseNumber(cell, option, "a number"));
    if (p.size() != 3 || !(p[2] > 0) || !(p[1] >= p[0]))
      throw Error(option + ": expected START:END:STEP with END >= START and STEP > 0, found '" +
                  text + "'");
    const double count = std::floor((p[1] - p[0]) / p[2] + 1e-9);
    if (count > 100000) throw Error(option + ": expected at most 100001 values, found " + text);
    const long n = std::lround(count);
    for (long i = 0; i <= n; ++i) out.push_back(p[0] + static_cast<double>(i) * p[2]);
    return out;
  }
  std::stringstream ss(text);
  std::string cell;
  while (std::getline(ss, cell, ',')) out.push_back(nx::parseNumber(cell, option, "a number"));
  return out;
}

// "X,Y,W,H" or "DX,DY".
std::vector<long> integers(const std::string& text, size_t count, const std::string& option) {
  std::vector<long> out;
  for (double v : numberList(text, option)) {
    if (v != std::floor(v) || std::abs(v) > 1e9)
      throw Error(option + ": expected whole numbers, found '" + text + "'");
    out.push_back(static_cast<long>(v));
  }
  if (out.size() != count)
    throw Error(option + ": expected " + std::to_string(count) +
                " comma-separated whole numbers, found '" + text + "'");
  return out;
}

std::string fixed(double v, int digits) {
  if (std::isnan(v)) return "-";
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", digits, v);
  return buf;
}

void writeText(const std::string& path, const std::string& text) {
  nx::writeAtomically(path, [&](const std::string& tmp) {
    std::ofstream f(tmp, std::ios::binary);
    f << text;
    if (!f.flush()) throw Error(tmp + ": cannot write");
  });
}

std::string general(double v) {
  if (std::isnan(v)) return "-";
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

} // namespace

int main(int argc, char** argv) {
  CLI::App app{"nxcompare: compares a render with a capture band by band"};
  std::string renderPath, capturePath, srf, wavelengths, fwhm, mask, scaleName = "none", crop,
                                                                     offset, csv, regionCsv;
  std::string samMap, plot, colourMode = "radiance", illuminantName = "D65";
  std::vector<std::string> rects;
  bool labels = false, skipNonFinite = false;
  double excludeAbove = std::numeric_limits<double>::infinity(), blackLevel = 0;
  double maxSam = -1, maxRelRmse = -1;
  app.add_option("render", renderPath, "The render (spectral EXR, ENVI cube or TIFF)")->required();
  app.add_option("capture", capturePath, "The capture (ENVI cube, TIFF or spectral EXR)")
      ->required();
  app.add_option(
      "--srf", srf,
      "CSV of the capture's band responses: nm,<band>,... (else Gaussians from its fwhm)");
  app.add_option("--capture-wavelengths", wavelengths,
                 "The capture's band centres when its file has none: a,b,c or START:END:STEP (nm)");
  app.add_option("--capture-fwhm", fwhm,
                 "The capture's band widths (nm): one value, or one per band");
  app.add_option("--rect", rects, "A region X,Y,W,H in render pixels (repeatable)");
  app.add_option("--mask", mask, "A PNG of the render's size: non-zero pixels are compared");
  app.add_flag("--labels", labels,
               "One region per object id (the render's ObjectId channel: --aov ids)");
  app.add_option("--scale", scaleName,
                 "Scale the render: none, global or band (least squares, reported)")
      ->check(CLI::IsMember({"none", "global", "band"}));
  app.add_option("--crop", crop, "Compare only the render's pixels X,Y,W,H");
  app.add_option("--offset", offset,
                 "DX,DY: render pixel (x, y) is capture pixel (x + DX, y + DY)");
  app.add_option("--csv", csv, "Per-band figures as CSV");
  app.add_option("--region-csv", regionCsv, "Per-region mean spectra as CSV");
  app.add_option("--black-level", blackLevel,
                 "Subtract this from every capture value first (a camera's offset in DN; "
                 "--exclude-above applies to the values as recorded)");
  app.add_option("--exclude-above", excludeAbove,
                 "Leave out pixels where a capture band reaches this value (saturation, e.g. the "
                 "full well in DN)");
  app.add_flag("--skip-nonfinite", skipNonFinite,
               "Leave out pixels with a NaN or infinite value instead of refusing them");
  app.add_option("--sam-map", samMap,
                 "The per-pixel spectral angle (degrees; NaN where none) as a float TIFF");
  app.add_option("--plot", plot,
                 "A PNG figure: per-band error, region spectra, spectral-angle map");
  app.add_option(
         "--colour", colourMode,
         "Region colours from radiance (white: the brightest region) or reflectance spectra")
      ->check(CLI::IsMember({"radiance", "reflectance"}));
  app.add_option("--illuminant", illuminantName,
                 "The white of the region colours (an illuminant name; default D65)");
  app.add_option("--max-sam", maxSam, "Exit 1 when the mean spectral angle exceeds DEG")
      ->check(nx::numberIn(0.0, 180.0));
  app.add_option("--max-relative-rmse", maxRelRmse, "Exit 1 when a band's relative RMSE exceeds R")
      ->check(nx::numberIn(0.0, 1e9));
  if (const int status = nx::parseCommandLine(app, argc, argv, "nxcompare", 2); status >= 0)
    return status;
  try {
    const std::optional<nx::Spectrum> illuminant = nx::namedEmission(illuminantName);
    if (!illuminant)
      throw Error("--illuminant: expected an illuminant name (D65, A, F11, ...), found '" +
                  illuminantName + "'");
    if (!plot.empty() && !nx::isPreviewPath(plot))
      throw Error("--plot: expected a .png or .bmp file name, found '" + plot + "'");
    // No output may replace an input (core/input_files.h).
    for (const std::string& in : {renderPath, capturePath, srf, mask})
      if (!in.empty()) nx::noteInputFile(in);
    for (const std::string& out : {csv, regionCsv, plot, samMap})
      if (!out.empty()) nx::checkWritable(out);
    nx::CubeReadOptions captureOptions;
    if (!wavelengths.empty())
      captureOptions.wavelengthNm = numberList(wavelengths, "--capture-wavelengths");
    if (!fwhm.empty()) captureOptions.fwhmNm = numberList(fwhm, "--capture-fwhm");
    const nx::SpectralCube render = nx::readSpectralCube(renderPath);
    const nx::SpectralCube capture = nx::readSpectralCube(capturePath, captureOptions);

    // Band matching. By identity when the capture was taken through the render's own bands:
    // the same sensor description (an nxcamera capture of the render, another render), or a
    // band list naming the render's bands (the SRF's nominal centres, as a camera's ENVI header
    // lists them); else through the capture's responses (--srf) or Gaussians.
    auto sameList = [&](const std::vector<double>& a, const std::vector<double>& b) {
      if (a.size() != b.size()) return false;
      for (size_t i = 0; i < a.size(); ++i)
        if (std::abs(a[i] - b[i]) > 0.01) return false;
      return true;
    };
    const bool sameSensor = !render.sensorText.empty() && render.sensorText == capture.sensorText;
    const bool sameCentroids = sameList(render.wavelengthNm, capture.wavelengthNm);
    const bool sameNames = !sameCentroids && sameList(render.channelNm, capture.channelNm);
    nx::BandResampling resampling = nx::BandResampling::identity(render.bands());
    std::string matching = sameSensor  ? "paired by identity (the render's own sensor)"
                           : sameNames ? "paired by identity (the render's band list, its "
                                         "nominal centres)"
                                       : "identical bands";
    const bool same = sameSensor || sameCentroids || sameNames;
    std::optional<nx::Sensor> responses;
    if (!srf.empty()) responses = nx::Sensor::readCsv(srf);
    if (responses && !render.sensorText.empty() && responses->toString() == render.sensorText) {
      // The render was recorded through these responses already: resampling again would apply
      // them twice.
      if (responses->count() != capture.bands())
        throw Error(srf + ": expected " + std::to_string(capture.bands()) +
                    " band responses (the capture's bands), found " +
                    std::to_string(responses->count()));
      matching = "paired by identity (" + srf + " is the render's own sensor)";
    } else if (responses) {
      if (responses->count() != capture.bands())
        throw Error(srf + ": expected " + std::to_string(capture.bands()) +
                    " band responses (the capture's bands), found " +
                    std::to_string(responses->count()));
      resampling = nx::BandResampling::through(render.wavelengthNm, *responses, capturePath);
      matching = "render resampled through the responses in " + srf;
    } else if (!same) {
      if (capture.fwhmNm.empty())
        throw Error(capturePath + ": its " + std::to_string(capture.bands()) + " bands (" +
                    general(capture.wavelengthNm.front()) + "-" +
                    general(capture.wavelengthNm.back()) + " nm) differ from the render's " +
                    std::to_string(render.bands()) + " (" + general(render.wavelengthNm.front()) +
                    "-" + general(render.wavelengthNm.back()) +
                    " nm) and it gives no fwhm: expected --capture-fwhm or --srf");
      const nx::Sensor gauss =
          nx::Sensor::gaussian(capture.wavelengthNm, capture.fwhmNm, capturePath);
      resampling = nx::BandResampling::through(render.wavelengthNm, gauss, capturePath);
      matching = "render resampled through Gaussian bands (the capture's fwhm)";
    }

    // The compared window: the crop in the render, the offset into the capture.
    long cx = 0, cy = 0, cw = render.width, ch = render.height, dx = 0, dy = 0;
    if (!crop.empty()) {
      const auto c = integers(crop, 4, "--crop");
      cx = c[0], cy = c[1], cw = c[2], ch = c[3];
      if (cx < 0 || cy < 0 || cw <= 0 || ch <= 0 || cx + cw > render.width ||
          cy + ch > render.height)
        throw Error("--crop: expected a window inside the render's " +
                    std::to_string(render.width) + " x " + std::to_string(render.height) +
                    " pixels, found " + crop);
    }
    if (!offset.empty()) {
      const auto o = integers(offset, 2, "--offset");
      dx = o[0], dy = o[1];
    }
    if (cx + dx < 0 || cy + dy < 0 || cx + dx + cw > capture.width || cy + dy + ch > capture.height)
      throw Error(
          capturePath + ": expected the compared window (" + std::to_string(cw) + " x " +
          std::to_string(ch) + " pixels at " + std::to_string(cx + dx) + "," +
          std::to_string(cy + dy) + " in the capture) inside its " + std::to_string(capture.width) +
          " x " + std::to_string(capture.height) + " pixels; the render is " +
          std::to_string(render.width) + " x " + std::to_string(render.height) +
          (crop.empty() && offset.empty() ? " (give --crop and --offset to align them)" : ""));

    // Both cubes on the window, the render through the capture's bands.
    const int nb = capture.bands();
    const size_t np = static_cast<size_t>(cw) * static_cast<size_t>(ch);
    std::vector<float> r(np * static_cast<size_t>(nb)), c(np * static_cast<size_t>(nb)), v, cv;
    const bool variance = !render.variance.empty();
    const bool captureVariance = !capture.variance.empty(); // a render compared as a capture
    if (variance) v.resize(r.size());
    if (captureVariance) cv.resize(c.size());
    for (long y = 0; y < ch; ++y)
      for (long x = 0; x < cw; ++x) {
        const size_t p = static_cast<size_t>(y * cw + x);
        const size_t rp = static_cast<size_t>((y + cy) * render.width + (x + cx));
        const size_t cp = static_cast<size_t>((y + cy + dy) * capture.width + (x + cx + dx));
        resampling.apply(&render.values[rp * static_cast<size_t>(render.bands())],
                         &r[p * static_cast<size_t>(nb)]);
        if (variance)
          resampling.applyToVariance(&render.variance[rp * static_cast<size_t>(render.bands())],
                                     &v[p * static_cast<size_t>(nb)]);
        for (int b = 0; b < nb; ++b) {
          const size_t i = p * static_cast<size_t>(nb) + static_cast<size_t>(b),
                       j = cp * static_cast<size_t>(nb) + static_cast<size_t>(b);
          c[i] = capture.values[j];
          if (captureVariance) cv[i] = capture.variance[j];
        }
      }

    // Pixels left out: saturated capture values, and non-finite values when asked.
    std::vector<uint8_t> excluded(np, 0);
    long saturated = 0, nonFinite = 0;
    for (size_t p = 0; p < np; ++p)
      for (int b = 0; b < nb; ++b) {
        const size_t i = p * static_cast<size_t>(nb) + static_cast<size_t>(b);
        if (skipNonFinite && (!std::isfinite(c[i]) || !std::isfinite(r[i]))) {
          nonFinite += excluded[p] ? 0 : 1;
          excluded[p] = 1;
        } else if (c[i] >= excludeAbove) {
          saturated += excluded[p] ? 0 : 1;
          excluded[p] = 1;
        }
      }
    if (blackLevel != 0)
      for (float& x : c) x = static_cast<float>(x - blackLevel);

    nx::ComparisonInputs in;
    in.excluded = excluded;
    in.width = static_cast<int>(cw);
    in.height = static_cast<int>(ch);
    in.bands = nb;
    in.originX = static_cast<int>(cx);
    in.originY = static_cast<int>(cy);
    in.wavelengthNm = capture.wavelengthNm;
    in.render = r.data();
    in.capture = c.data();
    in.renderVariance = variance ? v.data() : nullptr;
    in.captureVariance = captureVariance ? cv.data() : nullptr;
    // Regions, in render pixels, cut to the window.
    auto windowMask = [&](const std::function<bool(long, long)>& inside) {
      std::vector<uint8_t> m(np, 0);
      for (long y = 0; y < ch; ++y)
        for (long x = 0; x < cw; ++x)
          m[static_cast<size_t>(y * cw + x)] = inside(x + cx, y + cy) ? 1 : 0;
      return m;
    };
    for (const std::string& rect : rects) {
      const auto q = integers(rect, 4, "--rect");
      if (q[2] <= 0 || q[3] <= 0)
        throw Error("--rect: expected a positive width and height, found " + rect);
      in.regions.push_back({"rect " + rect, windowMask([&](long x, long y) {
                              return x >= q[0] && x < q[0] + q[2] && y >= q[1] && y < q[1] + q[3];
                            })});
    }
    if (!mask.empty()) {
      const nx::LinearSrgbImage m =
          nx::decodeSrgbImage(nx::readRegularFile(mask, 1ull << 31, "mask file"), mask);
      if (m.width != render.width || m.height != render.height)
        throw Error(mask + ": expected a mask of the render's " + std::to_string(render.width) +
                    " x " + std::to_string(render.height) + " pixels, found " +
                    std::to_string(m.width) + " x " + std::to_string(m.height));
      in.regions.push_back({"mask " + mask, windowMask([&](long x, long y) {
                              const size_t p = static_cast<size_t>(y * m.width + x) * 3;
                              return m.rgb[p] > 0 || m.rgb[p + 1] > 0 || m.rgb[p + 2] > 0;
                            })});
    }
    if (labels) {
      if (render.objectId.empty())
        throw Error(
            renderPath +
            ": expected an ObjectId channel for --labels (render with --aov ids), found none");
      std::map<uint32_t, bool> ids;
      for (long y = cy; y < cy + ch; ++y)
        for (long x = cx; x < cx + cw; ++x)
          ids[render.objectId[static_cast<size_t>(y * render.width + x)]] = true;
      for (const auto& [id, unused] : ids) {
        if (id == 0) continue;
        const auto label = render.objectLabels.find(id);
        in.regions.push_back(
            {label != render.objectLabels.end() ? label->second : "object " + std::to_string(id),
             windowMask([&, id = id](long x, long y) {
               return render.objectId[static_cast<size_t>(y * render.width + x)] == id;
             })});
      }
    }

    const nx::ScaleFit fit = scaleName == "global" ? nx::ScaleFit::Global
                             : scaleName == "band" ? nx::ScaleFit::PerBand
                                                   : nx::ScaleFit::None;
    nx::ComparisonReport rep;
    try {
      rep = nx::compareCubes(in, fit);
    } catch (const Error& e) {
      throw Error("comparing " + renderPath + " with " + capturePath + ": " + e.what());
    }

    nx::ColourOptions colours;
    colours.reflectance = colourMode == "reflectance";
    colours.illuminant = *illuminant;
    nx::addRegionColours(rep, capture.wavelengthNm, colours);

    std::printf("render  %s: %s, %d x %d, %d bands (%s-%s nm)\n", renderPath.c_str(),
                render.format.c_str(), render.width, render.height, render.bands(),
                general(render.wavelengthNm.front()).c_str(),
                general(render.wavelengthNm.back()).c_str());
    std::printf("capture %s: %s, %d x %d, %d bands (%s-%s nm)\n", capturePath.c_str(),
                capture.format.c_str(), capture.width, capture.height, capture.bands(),
                general(capture.wavelengthNm.front()).c_str(),
                general(capture.wavelengthNm.back()).c_str());
    std::printf(
        "bands: %s; %ld pixels compared%s\n", matching.c_str(), rep.pixels,
        in.regions.empty() ? "" : (" (" + std::to_string(in.regions.size()) + " regions)").c_str());
    if (saturated + nonFinite > 0)
      std::printf("left out: %ld pixels with a capture value at or above %s, %ld with non-finite "
                  "values (%ld of them in the compared regions)\n",
                  saturated, general(excludeAbove).c_str(), nonFinite, rep.excludedPixels);
    if (fit == nx::ScaleFit::Global)
      std::printf("scale (least squares, global): %.6g\n", rep.bands[0].scale);
    // The bands by their own names (the render's when paired by identity, else the
    // capture's), or by wavelength.
    const std::vector<std::string>& names =
        same && !render.bandNames.empty() ? render.bandNames : capture.bandNames;
    auto bandName = [&](size_t b) {
      return b < names.size() ? names[b] : fixed(rep.bands[b].wavelengthNm, 2) + " nm";
    };
    std::printf("\n%-12s %10s %10s %12s %12s %12s %12s %10s %8s %8s\n", "band", "nm", "scale",
                "render", "capture", "bias", "rmse", "rel.rmse", "psnr dB", "z");
    double worstRel = 0;
    for (size_t b = 0; b < rep.bands.size(); ++b) {
      const nx::BandFigures& f = rep.bands[b];
      std::printf(
          "%-12s %10s %10s %12s %12s %12s %12s %10s %8s %8s\n", bandName(b).c_str(),
          fixed(f.wavelengthNm, 2).c_str(), general(f.scale).c_str(), general(f.renderMean).c_str(),
          general(f.captureMean).c_str(), general(f.bias).c_str(), general(f.rmse).c_str(),
          fixed(f.relativeRmse, 4).c_str(), fixed(f.psnrDb, 1).c_str(), fixed(f.zMean, 2).c_str());
      worstRel = std::max(worstRel, std::abs(f.relativeRmse));
    }
    std::printf("\nspectral angle (degrees) over %ld pixels: mean %s, median %s, 95th percentile "
                "%s, max %s",
                rep.sam.pixels, fixed(rep.sam.meanDeg, 4).c_str(),
                fixed(rep.sam.medianDeg, 4).c_str(), fixed(rep.sam.p95Deg, 4).c_str(),
                fixed(rep.sam.maxDeg, 4).c_str());
    if (rep.sam.undefinedPixels > 0)
      std::printf(" (%ld pixels all zero on one side)", rep.sam.undefinedPixels);
    std::printf("\n");
    if (!rep.regions.empty())
      std::printf("\n%-24s %8s %10s %26s %26s %8s\n", "region", "pixels", "SAM deg",
                  ("render L*a*b* (" + colourMode + ", " + illuminantName + ")").c_str(),
                  "capture L*a*b*", "dE2000");
    for (const nx::RegionFigures& g : rep.regions) {
      auto lab = [&g](const nx::Lab& l) {
        return g.pixels == 0 ? std::string("-")
                             : fixed(l.l, 2) + " " + fixed(l.a, 2) + " " + fixed(l.b, 2);
      };
      std::printf("%-24s %8ld %10s %26s %26s %8s\n", g.name.c_str(), g.pixels,
                  fixed(g.samMeanDeg, 4).c_str(), lab(g.renderLab).c_str(),
                  lab(g.captureLab).c_str(), fixed(g.deltaE2000, 3).c_str());
    }

    if (!csv.empty()) {
      std::ostringstream out;
      out << "band,wavelength_nm,rmse,relative_rmse,bias,psnr_db,render_mean,capture_mean,scale,"
             "z_mean,rms_z\n";
      for (size_t b = 0; b < rep.bands.size(); ++b) {
        const nx::BandFigures& f = rep.bands[b];
        std::string name = bandName(b);
        std::replace(name.begin(), name.end(), ',', ';');
        out << name << ',' << general(f.wavelengthNm) << ',' << general(f.rmse) << ','
            << general(f.relativeRmse) << ',' << general(f.bias) << ',' << general(f.psnrDb) << ','
            << general(f.renderMean) << ',' << general(f.captureMean) << ',' << general(f.scale)
            << ',' << general(f.zMean) << ',' << general(f.rmsZ) << '\n';
      }
      writeText(csv, out.str());
    }
    if (!regionCsv.empty()) {
      std::ostringstream out;
      out << "region,pixels,side,L,a,b,delta_e_2000";
      for (double nm : capture.wavelengthNm) out << ',' << general(nm);
      out << '\n';
      for (const nx::RegionFigures& g : rep.regions)
        for (int side = 0; side < 2; ++side) {
          const nx::Lab& l = side ? g.captureLab : g.renderLab;
          out << '"' << g.name << "\"," << g.pixels << ',' << (side ? "capture" : "render") << ','
              << general(l.l) << ',' << general(l.a) << ',' << general(l.b) << ','
              << general(g.deltaE2000);
          for (double x : side ? g.captureMean : g.renderMean) out << ',' << general(x);
          out << '\n';
        }
      writeText(regionCsv, out.str());
    }
    if (!plot.empty()) nx::writeComparisonFigure(plot, rep, in.width, in.height);
    if (!samMap.empty())
      nx::writeFloatTiff(samMap, in.width, in.height, rep.samMapDeg,
                         "spectral angle (degrees) between " + renderPath + " and " + capturePath);
    bool pass = true;
    if (maxSam >= 0 && !(rep.sam.meanDeg <= maxSam)) {
      std::printf("FAIL: mean spectral angle %s exceeds %s degrees\n",
                  fixed(rep.sam.meanDeg, 4).c_str(), general(maxSam).c_str());
      pass = false;
    }
    if (maxRelRmse >= 0 && !(worstRel <= maxRelRmse)) {
      std::printf("FAIL: relative RMSE %s exceeds %s\n", fixed(worstRel, 4).c_str(),
                  general(maxRelRmse).c_str());
      pass = false;
    }
    return pass ? 0 : 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "nxcompare: error: %s\n", e.what());
    return 2;
  }
}
