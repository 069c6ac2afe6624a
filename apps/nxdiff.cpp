// nxdiff: compares two spectral EXR images written by nxrender or nxmerge.
//
//   nxdiff A.exr B.exr [--max-relative R]
//
// Prints the largest absolute and relative differences of the spectral and XYZ channels (the
// data) and of the RGB channels (derived from XYZ through a matrix with negative entries, so
// tiny values there can differ much more in relative terms), and whether the sample counts
// agree. Exit status 0 when the counts agree, the spectral and XYZ channels differ by at most
// R relatively (default 0: identical bit for bit) and RGB is identical when R is 0; 1
// otherwise; 2 on errors.

#include <CLI/CLI.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "io/spectral_exr.h"

int main(int argc, char** argv) {
  CLI::App app{"nxdiff: compares two nxrender images"};
  std::string a, b;
  double maxRelative = 0;
  app.add_option("a", a, "First EXR")->required();
  app.add_option("b", b, "Second EXR")->required();
  app.add_option("--max-relative", maxRelative, "Largest relative difference accepted (default 0)")
      ->check(CLI::Range(0.0, 1e9));
  CLI11_PARSE(app, argc, argv);
  try {
    const nx::SpectralImage x = nx::readSpectralExr(a), y = nx::readSpectralExr(b);
    if (x.width != y.width || x.height != y.height || x.originX != y.originX ||
        x.originY != y.originY || x.bands.toString() != y.bands.toString()) {
      std::printf("nxdiff: the images differ in size, position or bands\n");
      return 1;
    }
    struct Stats {
      double maxAbs = 0, maxRel = 0;
      bool sizes = true;
    };
    auto compare = [](const std::vector<float>& u, const std::vector<float>& v, Stats& st) {
      st.sizes = st.sizes && u.size() == v.size();
      for (size_t i = 0; i < u.size() && i < v.size(); ++i) {
        const double d = std::abs(static_cast<double>(u[i]) - v[i]);
        st.maxAbs = std::max(st.maxAbs, d);
        const double scale =
            std::max(std::abs(static_cast<double>(u[i])), std::abs(static_cast<double>(v[i])));
        if (d > 0) st.maxRel = std::max(st.maxRel, scale > 0 ? d / scale : INFINITY);
      }
    };
    Stats data, rgb;
    compare(x.radiance, y.radiance, data);
    compare(x.xyz, y.xyz, data);
    compare(x.rgb, y.rgb, rgb);
    const bool countsEqual = x.sampleCount == y.sampleCount;
    std::printf("nxdiff: spectral+XYZ max absolute difference %.9g, max relative %.9g; RGB max "
                "absolute %.9g; "
                "sample counts %s\n",
                data.maxAbs, data.maxRel, rgb.maxAbs, countsEqual ? "equal" : "differ");
    const bool ok = data.sizes && rgb.sizes && countsEqual && data.maxRel <= maxRelative &&
                    (maxRelative > 0 || rgb.maxAbs == 0);
    return ok ? 0 : 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "nxdiff: error: %s\n", e.what());
    return 2;
  }
}
