// nxbench-exr: the spectral EXR's size against its writing time, for every OpenEXR
// compression method, zip levels, and half floats.
//
//   nxbench-exr IMAGE.exr [--threads N] [--repeats R] [--dir DIR]
//
// Reads a spectral EXR written by nxrender, writes it again with each encoding (fastest of R
// writes, N threads compressing line blocks), reads each result back and prints: the file's
// size, the write and read seconds, and whether the bands came back bit for bit (else the
// largest relative change of a band value). Also counts how many variance values half floats
// would lose (below the smallest normal half, 6.1e-5, or flushed to zero).

#include <CLI/CLI.hpp>
#include <tbb/global_control.h>

#include <cmath>
#include <cstdio>
#include <filesystem>

#include "apps/bench_util.h"
#include "apps/command_line.h"
#include "apps/program_main.h"
#include "core/error.h"
#include "io/spectral_exr.h"

namespace {

// The largest relative change of a band value (0: bit for bit), relative to the band's
// largest value in the image so that dark pixels do not dominate.
double largestBandChange(const nx::SpectralImage& a, const nx::SpectralImage& b) {
  const int nb = a.bands.count();
  std::vector<double> peak(static_cast<size_t>(nb), 0.0);
  for (size_t i = 0; i < a.radiance.size(); ++i)
    peak[i % nb] = std::max(peak[i % nb], std::abs(static_cast<double>(a.radiance[i])));
  double worst = 0;
  for (size_t i = 0; i < a.radiance.size(); ++i) {
    const double d = std::abs(static_cast<double>(a.radiance[i]) - b.radiance[i]);
    if (d > 0) worst = std::max(worst, peak[i % nb] > 0 ? d / peak[i % nb] : HUGE_VAL);
  }
  return worst;
}

int run(int argc, char** argv) {
  CLI::App app{"nxbench-exr: spectral EXR size against write time for each compression"};
  std::string input, dir = std::filesystem::temp_directory_path().string();
  int threads = 2, repeats = 3;
  app.add_option("image", input, "A spectral EXR written by nxrender")->required();
  app.add_option("--threads", threads, "Threads compressing line blocks")
      ->check(nx::numberIn(1, 256));
  app.add_option("--repeats", repeats, "Writes per encoding (the fastest counts)")
      ->check(nx::numberIn(1, 100));
  app.add_option("--dir", dir, "Where the test files go (removed afterwards)");
  if (const int status = nx::parseCommandLine(app, argc, argv, "nxbench-exr"); status >= 0)
    return status;
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism,
                            static_cast<size_t>(threads));

  const nx::SpectralImage image = nx::readSpectralExr(input);
  const size_t pixels = static_cast<size_t>(image.width) * image.height;
  std::printf("%s: %dx%d, %d bands, %zu float values per pixel, %d threads\n", input.c_str(),
              image.width, image.height, image.bands.count(),
              (image.radiance.size() + image.rgb.size() + image.xyz.size() +
               image.bandVariance.size() + image.yVariance.size()) /
                  pixels,
              threads);

  size_t lost = 0, nonzero = 0;
  for (float v : image.bandVariance)
    if (v != 0) {
      ++nonzero;
      if (std::abs(v) < 6.103515625e-5f) ++lost;
    }
  std::printf("variance values below the smallest normal half float: %zu of %zu non-zero "
              "(%.1f%%)\n\n",
              lost, nonzero,
              nonzero ? 100.0 * static_cast<double>(lost) / static_cast<double>(nonzero) : 0.0);

  std::printf("| encoding | size MB | write s | read s | bands |\n|---|---|---|---|---|\n");
  const std::string path = (std::filesystem::path(dir) / "nxbench-exr.exr").string();
  const bool halfOk = nx::fitsInHalf(image);
  for (bool half : {false, true}) {
    if (half && !halfOk) {
      std::printf("(half floats: skipped, values beyond 65504)\n");
      continue;
    }
    for (nx::ExrCompression c : nx::allExrCompressions()) {
      const bool zip = c == nx::ExrCompression::Zip || c == nx::ExrCompression::Zips;
      for (int level : zip ? std::vector<int>{1, 4, 6, 9} : std::vector<int>{1}) {
        const nx::ExrEncoding enc{c, level};
        const double write = nx::bench::fastestSeconds(repeats, [&] {
          if (half)
            nx::writeSpectralExrHalf(path, image, enc);
          else
            nx::writeSpectralExr(path, image, enc);
        });
        const double mb = static_cast<double>(std::filesystem::file_size(path)) / 1e6;
        nx::SpectralImage back;
        const double read =
            nx::bench::fastestSeconds(repeats, [&] { back = nx::readSpectralExr(path); });
        const double change = largestBandChange(image, back);
        char what[64];
        if (change == 0)
          std::snprintf(what, sizeof what, "exact");
        else
          std::snprintf(what, sizeof what, "%.2g of band peak", change);
        std::printf("| %s%s%s%s | %.2f | %.3f | %.3f | %s |\n", half ? "half, " : "",
                    nx::exrCompressionName(c), zip ? " level " : "",
                    zip ? std::to_string(level).c_str() : "", mb, write, read, what);
      }
    }
  }
  std::filesystem::remove(path);
  return 0;
}

} // namespace

int main(int argc, char** argv) {
  return nx::mainReportingErrors("nxbench-exr", run, argc, argv);
}
