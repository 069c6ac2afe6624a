// nxbench-adaptive: time to an image error with adaptive sampling against uniform sampling.
//
//   nxbench-adaptive scene.scn --reference REF.exr [--max-spp N] [--targets a,b,c]
//                    [--bias-seeds K] [--threads N] [--csv OUT.csv] [--plot OUT.png]
//
// Uniform renders at 16, 32, ... max-spp and adaptive renders (`--adaptive --target-error E`
// for each target E, at most 4 x max-spp per pixel), all measured against the reference: render
// seconds, samples, the estimated and the true relative RMSE of the luminance. For each
// adaptive render it reads the uniform curve (log-log interpolation) at the same true error and
// prints the speed-up: uniform time over adaptive time. With --bias-seeds K it also renders the
// first target K times with other seeds and reports the bias of error-driven stopping: the mean
// over seeds of the image's mean luminance against the reference's, with its standard error,
// and the RMSE of the seeds' average image against the reference compared with one render's
// RMSE over sqrt(K) (what it would be with no bias).

#include <CLI/CLI.hpp>
#include <tbb/global_control.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "apps/bench_errors.h"
#include "apps/command_line.h"
#include "apps/log_plot.h"
#include "apps/program_main.h"
#include "core/error.h"
#include "core/text_table.h"
#include "integrators/renderer.h"
#include "integrators/scene_reader.h"
#include "io/preview_image.h"

namespace {

using namespace nx;

// The uniform curve's time at error `e` (log-log interpolation; extrapolated at the ends).
double uniformTimeAt(const std::vector<double>& t, const std::vector<double>& err, double e) {
  size_t k = 0;
  while (k + 2 < err.size() && err[k + 1] > e) ++k;
  const double a = std::log(err[k]), b = std::log(err[k + 1]);
  const double f = (std::log(e) - a) / (b - a);
  return std::exp(std::log(t[k]) + f * (std::log(t[k + 1]) - std::log(t[k])));
}

double meanY(const Film& f) {
  double s = 0;
  for (int y = 0; y < f.height(); ++y)
    for (int x = 0; x < f.width(); ++x) s += f.xyzMean(x, y).y;
  return s / (static_cast<double>(f.width()) * f.height());
}

int run(int argc, char** argv) {
  CLI::App app{"nxbench-adaptive: time to an error, adaptive against uniform sampling"};
  std::string scenePath, referencePath, targetsText = "0.4,0.2,0.1",
                                        csvPath = "nxbench-adaptive.csv",
                                        plotPath = "nxbench-adaptive.png";
  int maxSpp = 256, threads = 2, biasSeeds = 0;
  app.add_option("scene", scenePath, "Scene file")->required();
  app.add_option("--reference", referencePath, "Reference EXR of the scene")->required();
  app.add_option("--max-spp", maxSpp, "Largest spp of the uniform series (default 256)")
      ->check(nx::numberIn(16, 1 << 20));
  app.add_option("--targets", targetsText, "Adaptive target errors, a comma list");
  app.add_option("--bias-seeds", biasSeeds, "Renders of the first target for the bias (0: none)")
      ->check(nx::numberIn(0, 1000));
  app.add_option("--threads", threads, "Threads (default 2)")->check(nx::numberIn(1, 4096));
  app.add_option("--csv", csvPath, "CSV output");
  app.add_option("--plot", plotPath, "Error-against-time plot, PNG");
  std::string replot;
  app.add_option("--replot", replot, "Only draw the plot again from this CSV of an earlier run");
  if (const int status = nx::parseCommandLine(app, argc, argv, "nxbench-adaptive"); status >= 0)
    return status;
  const std::string title = std::filesystem::path(scenePath).filename().string();
  if (!replot.empty()) {
    std::ifstream in(replot);
    if (!in) throw Error(replot + ": cannot read");
    PlotSeries series[2] = {{"uniform", {}, {}, 200, 40, 40, false},
                            {"adaptive", {}, {}, 30, 110, 200, false}};
    std::string line;
    std::getline(in, line); // the header
    while (std::getline(in, line)) {
      std::vector<std::string> f;
      std::stringstream row(line);
      for (std::string item; std::getline(row, item, ',');) f.push_back(item);
      if (f.size() != 6) throw Error(replot + ": expected 6 columns, found '" + line + "'");
      PlotSeries& p = series[f[0] == "adaptive" ? 1 : 0];
      p.x.push_back(parseNumber(f[3], replot, "seconds"));
      p.y.push_back(parseNumber(f[5], replot, "an error"));
    }
    writePreview(plotPath, 720, 480,
                 renderLogLogPlot({series[0], series[1]}, "render time (s)",
                                  "relative RMSE of luminance", title, 720, 480));
    return 0;
  }
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism,
                            static_cast<size_t>(threads));
  const RenderScene scene = buildRenderScene(loadScene(scenePath));
  const SpectralImage ref = readSpectralExr(referencePath);
  if (ref.width != scene.settings.width || ref.height != scene.settings.height || ref.xyz.empty())
    throw Error(referencePath + ": does not match the scene's size (or has no XYZ channels)");
  // The reference's own estimated relative error (its Variance.Y), taken out of each measured
  // error in quadrature (the reference and the render are independent).
  double refRel = 0;
  if (!ref.yVariance.empty()) {
    double v = 0, m = 0;
    for (size_t i = 0; i < ref.yVariance.size(); ++i)
      v += ref.yVariance[i], m += ref.xyz[i * 3 + 1];
    refRel = std::sqrt(v / static_cast<double>(ref.yVariance.size())) /
             (m / static_cast<double>(ref.yVariance.size()));
  }
  auto trueError = [&](const Film& f) {
    const double e = bench::compareWithReference(f, ref).relY;
    return std::sqrt(std::max(0.0, e * e - refRel * refRel));
  };
  std::printf("reference's estimated relative error %.4f (removed in quadrature)\n\n", refRel);
  std::vector<double> targets;
  {
    std::stringstream in(targetsText);
    std::string item;
    while (std::getline(in, item, ','))
      targets.push_back(parseNumber(item, "--targets", "a relative error"));
  }

  std::ofstream csv(csvPath);
  csv << "mode,target,spp_mean,seconds,estimated_rel_rmse_Y,true_rel_rmse_Y\n";
  std::printf("| sampling | target | mean spp | seconds | estimated error | true error | "
              "uniform s at that error | speed-up |\n|---|---|---|---|---|---|---|---|\n");
  PlotSeries uniform{"uniform", {}, {}, 200, 40, 40, false};
  PlotSeries adaptive{"adaptive", {}, {}, 30, 110, 200, false};
  const double pixels = static_cast<double>(ref.width) * ref.height;
  for (int spp = 16; spp <= maxSpp; spp *= 2) {
    RenderOptions o;
    o.samples = spp;
    const RenderOutput out = render(scene, o);
    const double err = trueError(out.film);
    uniform.x.push_back(out.stats.seconds);
    uniform.y.push_back(err);
    std::printf("| uniform | | %d | %.3f | %.4f | %.4f | | |\n", spp, out.stats.seconds,
                out.film.relativeRmsError(), err);
    csv << "uniform,," << spp << "," << out.stats.seconds << "," << out.film.relativeRmsError()
        << "," << err << "\n";
  }
  for (double target : targets) {
    RenderOptions o;
    o.samples = 4 * maxSpp;
    o.adaptive = true;
    o.targetRelativeError = target;
    const RenderOutput out = render(scene, o);
    const double err = trueError(out.film);
    const double spp = static_cast<double>(out.stats.samples) / pixels;
    const double tu = uniformTimeAt(uniform.x, uniform.y, err);
    adaptive.x.push_back(out.stats.seconds);
    adaptive.y.push_back(err);
    std::printf("| adaptive | %g | %.1f | %.3f | %.4f | %.4f | %.3f | %.2fx |\n", target, spp,
                out.stats.seconds, out.stats.relativeError, err, tu, tu / out.stats.seconds);
    csv << "adaptive," << target << "," << spp << "," << out.stats.seconds << ","
        << out.stats.relativeError << "," << err << "\n";
  }
  if (biasSeeds > 0 && !targets.empty()) {
    // The bias of error-driven stopping: K independent adaptive renders of the first target.
    const double refMean = [&] {
      double s = 0;
      for (size_t i = 0; i < ref.xyz.size(); i += 3) s += ref.xyz[i + 1];
      return s / pixels;
    }();
    std::vector<double> rel;
    std::vector<double> sumY(static_cast<size_t>(pixels), 0.0);
    double singleErr = 0;
    for (int k = 0; k < biasSeeds; ++k) {
      RenderOptions o;
      o.samples = 4 * maxSpp;
      o.adaptive = true;
      o.targetRelativeError = targets.front();
      o.seed = 1000u + static_cast<uint32_t>(k);
      const RenderOutput out = render(scene, o);
      rel.push_back(meanY(out.film) / refMean - 1);
      singleErr += trueError(out.film) / biasSeeds;
      for (int y = 0; y < ref.height; ++y)
        for (int x = 0; x < ref.width; ++x)
          sumY[static_cast<size_t>(y) * ref.width + x] += out.film.xyzMean(x, y).y;
    }
    double m = 0, v = 0;
    for (double r : rel) m += r / biasSeeds;
    for (double r : rel) v += (r - m) * (r - m) / std::max(1, biasSeeds - 1);
    double se = 0;
    for (size_t i = 0; i < sumY.size(); ++i) {
      const double d = sumY[i] / biasSeeds - ref.xyz[i * 3 + 1];
      se += d * d;
    }
    std::printf("\nbias at target %g over %d seeds: image mean luminance %+.2e relative to the "
                "reference (standard error %.2e); RMSE of the seeds' average %.4g of the mean, "
                "one render's over sqrt(K) %.4g\n",
                targets.front(), biasSeeds, m, std::sqrt(v / biasSeeds),
                std::sqrt(se / pixels) / refMean, singleErr / std::sqrt(biasSeeds));
  }
  writePreview(plotPath, 720, 480,
               renderLogLogPlot({uniform, adaptive}, "render time (s)",
                                "relative RMSE of luminance", title, 720, 480));
  std::fprintf(stderr, "nxbench-adaptive: wrote %s and %s\n", csvPath.c_str(), plotPath.c_str());
  return 0;
}

} // namespace

int main(int argc, char** argv) {
  return nx::mainReportingErrors("nxbench-adaptive", run, argc, argv);
}
