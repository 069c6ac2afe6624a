// nxdiff: compares two spectral EXR images written by nxrender or nxmerge.
//
//   nxdiff A.exr B.exr [--max-relative R]
//
// Prints the largest absolute and relative differences of the spectral and XYZ channels (the
// data) and of the RGB channels (derived from XYZ through a matrix with negative entries, so
// tiny values there can differ much more in relative terms), and whether the sample counts
// agree; names what differs when the size, position or bands do, which bands differ and by
// how much, and which provenance attributes differ (reported only). Per-band error figures of
// two different renders (RMSE, bias, spectral angle, noise z-scores): nxcompare. Exit status 0 when
// the counts agree, no value is NaN or infinite (a NaN is never equal to anything), the spectral
// and XYZ channels differ by at most R relatively (default 0: identical bit for bit) and RGB
// is identical when R is 0; 1 otherwise; 2 on errors.

#include <CLI/CLI.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "apps/command_line.h"
#include "io/spectral_exr.h"

int main(int argc, char** argv) {
  CLI::App app{"nxdiff: compares two nxrender images"};
  std::string a, b;
  double maxRelative = 0;
  app.add_option("a", a, "First EXR")->required();
  app.add_option("b", b, "Second EXR")->required();
  app.add_option("--max-relative", maxRelative, "Largest relative difference accepted (default 0)")
      ->check(nx::numberIn(0.0, 1e9));
  if (const int status = nx::parseCommandLine(app, argc, argv, "nxdiff"); status >= 0)
    return status;
  try {
    const nx::SpectralImage x = nx::readSpectralExr(a), y = nx::readSpectralExr(b);
    // Say which of size, position and bands differ, with both values.
    std::string layout;
    auto differs = [&](const char* what, const std::string& u, const std::string& v) {
      if (u != v) layout += std::string(layout.empty() ? "" : "; ") + what + " " + u + " vs " + v;
    };
    differs("size", std::to_string(x.width) + "x" + std::to_string(x.height),
            std::to_string(y.width) + "x" + std::to_string(y.height));
    differs("position", std::to_string(x.originX) + "," + std::to_string(x.originY),
            std::to_string(y.originX) + "," + std::to_string(y.originY));
    differs("bands", x.bands.toString(), y.bands.toString());
    if (!layout.empty()) {
      std::printf("nxdiff: the images differ: %s\n", layout.c_str());
      return 1;
    }
    // Provenance attributes that differ (reported, not failed: timings and hosts differ).
    for (const auto& [key, value] : x.attributes) {
      const auto it = y.attributes.find(key);
      if (it == y.attributes.end())
        std::printf("nxdiff: attribute %s only in %s\n", key.c_str(), a.c_str());
      else if (it->second != value && value.size() + it->second.size() < 200)
        std::printf("nxdiff: attribute %s: '%s' vs '%s'\n", key.c_str(), value.c_str(),
                    it->second.c_str());
      else if (it->second != value)
        std::printf("nxdiff: attribute %s differs\n", key.c_str());
    }
    for (const auto& [key, value] : y.attributes)
      if (!x.attributes.count(key))
        std::printf("nxdiff: attribute %s only in %s\n", key.c_str(), b.c_str());
    struct Stats {
      double maxAbs = 0, maxRel = 0;
      bool sizes = true;
      size_t nonFinite = 0; ///< positions where either value is NaN or infinite
    };
    // A non-finite value never equals anything (NaN would compare as "no difference").
    auto compare = [](const std::vector<float>& u, const std::vector<float>& v, Stats& st) {
      st.sizes = st.sizes && u.size() == v.size();
      for (size_t i = 0; i < u.size() && i < v.size(); ++i) {
        if (!std::isfinite(u[i]) || !std::isfinite(v[i])) {
          ++st.nonFinite;
          continue;
        }
        const double d = std::abs(static_cast<double>(u[i]) - v[i]);
        st.maxAbs = std::max(st.maxAbs, d);
        const double scale =
            std::max(std::abs(static_cast<double>(u[i])), std::abs(static_cast<double>(v[i])));
        if (d > 0) st.maxRel = std::max(st.maxRel, scale > 0 ? d / scale : INFINITY);
      }
    };
    // Per band: which bands differ, and by how much.
    const int nb = x.bands.count();
    int identicalBands = 0;
    for (int band = 0; band < nb && x.radiance.size() == y.radiance.size(); ++band) {
      std::vector<float> u, v;
      for (size_t i = static_cast<size_t>(band); i < x.radiance.size();
           i += static_cast<size_t>(nb))
        u.push_back(x.radiance[i]), v.push_back(y.radiance[i]);
      Stats st;
      compare(u, v, st);
      if (st.maxAbs == 0 && st.nonFinite == 0) {
        ++identicalBands;
        continue;
      }
      std::printf("nxdiff: band %g nm: max absolute difference %.9g, max relative %.9g%s\n",
                  x.bands.centroid(band), st.maxAbs, st.maxRel,
                  st.nonFinite
                      ? (", " + std::to_string(st.nonFinite) + " values NaN or infinite").c_str()
                      : "");
    }
    std::printf("nxdiff: %d of %d bands identical\n", identicalBands, nb);
    Stats data, rgb;
    compare(x.radiance, y.radiance, data);
    compare(x.xyz, y.xyz, data);
    compare(x.rgb, y.rgb, rgb);
    if (data.nonFinite + rgb.nonFinite > 0)
      std::printf("nxdiff: %zu values are NaN or infinite in one of the images\n",
                  data.nonFinite + rgb.nonFinite);
    const bool countsEqual = x.sampleCount == y.sampleCount;
    std::printf("nxdiff: spectral+XYZ max absolute difference %.9g, max relative %.9g; RGB max "
                "absolute %.9g; "
                "sample counts %s\n",
                data.maxAbs, data.maxRel, rgb.maxAbs, countsEqual ? "equal" : "differ");
    const bool ok = data.sizes && rgb.sizes && countsEqual && data.nonFinite + rgb.nonFinite == 0 &&
                    data.maxRel <= maxRelative && (maxRelative > 0 || rgb.maxAbs == 0);
    return ok ? 0 : 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "nxdiff: error: %s\n", e.what());
    return 2;
  }
}
