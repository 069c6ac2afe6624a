// nxbench: speed against error for one scene.
//
//   nxbench scene.scn [--reference REF.exr | --reference-spp N] [--max-spp N] [--threads N]
//                     [--sampler sobol|independent] [--bands START:END:STEP]
//                     [--wavelength-density sensor|visible] [--csv OUT.csv] [--plot OUT.png]
//
// Renders (or reads) a high-spp reference, then renders at 1, 2, 4, ... spp and prints, per
// run: seconds, samples/s, rays/s, RMSE and relative RMSE of the preview luminance and of the
// spectral bands (mean and worst band) against the reference, and the fitted convergence
// slope of the relative RMSE (an unbiased renderer gives -0.5 or steeper). It also measures
// raw Embree ray throughput on the scene's geometry and the path tracer's ratio to it.
// The CSV holds every band's RMSE; the plot shows relative RMSE against time, log-log, of the
// luminance, the mean band and the worst band.

#include <CLI/CLI.hpp>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "apps/bench_errors.h"
#include "apps/command_line.h"
#include "apps/log_plot.h"
#include "core/error.h"
#include "core/hash.h"
#include "core/math_util.h"
#include "integrators/renderer.h"
#include "integrators/sampling.h"
#include "integrators/scene_reader.h"
#include "io/preview_image.h"

namespace {

using namespace nx;

// Closest-hit rays per second through the scene's geometry: origins uniform in the bounding
// box of its spheres, triangles and camera, directions uniform. The rays are made before the
// clock starts, so the figure is the queries' alone.
double rawRaysPerSecond(const RenderScene& scene) {
  BoundingBox box = scene.geometry->bounds();
  const Ray camRay =
      scene.camera.generateRay(0.5 * scene.settings.width, 0.5 * scene.settings.height);
  box.add(Vec3d(camRay.o));
  const Vec3d lo = box.lo, hi = box.hi;
  const uint64_t rays = 4000000;
  std::vector<Ray> batch(rays);
  tbb::parallel_for(
      tbb::blocked_range<uint64_t>(0, rays, 8192), [&](const tbb::blocked_range<uint64_t>& r) {
        for (uint64_t i = r.begin(); i != r.end(); ++i) {
          const uint32_t k = static_cast<uint32_t>(i);
          auto u = [&](uint32_t d) {
            return static_cast<double>(bitsToUnitFloat(hash4(k, d, 0xbe9c, 0)));
          };
          Ray& ray = batch[i];
          ray.o = Vec3(Vec3d(lo.x + (hi.x - lo.x) * u(0), lo.y + (hi.y - lo.y) * u(1),
                             lo.z + (hi.z - lo.z) * u(2)));
          ray.d = sampleUniformSphere({static_cast<float>(u(3)), static_cast<float>(u(4))});
        }
      });
  std::atomic<uint64_t> hits{0};
  const auto start = std::chrono::steady_clock::now();
  tbb::parallel_for(tbb::blocked_range<uint64_t>(0, rays, 8192),
                    [&](const tbb::blocked_range<uint64_t>& r) {
                      uint64_t local = 0;
                      SurfaceHit h;
                      for (uint64_t i = r.begin(); i != r.end(); ++i)
                        local += scene.geometry->intersect(batch[i], h);
                      hits += local;
                    });
  return static_cast<double>(rays) /
         std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

} // namespace

int main(int argc, char** argv) {
  CLI::App app{"nxbench: speed against error for one scene"};
  std::string scenePath, referencePath, csvPath = "nxbench.csv", plotPath = "nxbench.png",
                                        sampler = "stratified", bandsText, density = "sensor";
  int referenceSpp = 1024, maxSpp = 64, threads = 2;
  app.add_option("scene", scenePath, "Scene file")->required();
  app.add_option("--reference", referencePath, "Reference EXR (else rendered)");
  app.add_option("--reference-spp", referenceSpp,
                 "Samples per pixel of the rendered reference (default 1024)")
      ->check(nx::numberIn(1, 1 << 24));
  app.add_option("--max-spp", maxSpp, "Largest spp of the doubling series (default 64)")
      ->check(nx::numberIn(1, 1 << 20));
  app.add_option("--threads", threads, "Threads (default 2)")->check(nx::numberIn(1, 4096));
  app.add_option("--sampler", sampler, "stratified (default), sobol or independent, as nxrender's")
      ->check(CLI::IsMember({"stratified", "sobol", "independent"}));
  app.add_option("--bands", bandsText, "Bands START:END:STEP in nm (default: the scene's)");
  app.add_option("--wavelength-density", density, "sensor (default) or visible")
      ->check(CLI::IsMember({"sensor", "visible"}));
  app.add_option("--csv", csvPath, "CSV output (default nxbench.csv)");
  app.add_option("--plot", plotPath, "Error-against-time plot, PNG (default nxbench.png)");
  if (const int status = nx::parseCommandLine(app, argc, argv, "nxbench"); status >= 0)
    return status;
  try {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism,
                              static_cast<size_t>(threads));
    const RenderScene scene = buildRenderScene(loadScene(scenePath));
    const SamplerKind kind =
        sampler == "independent" ? SamplerKind::Independent : SamplerKind::SobolOwen;
    const Sensor bands =
        bandsText.empty() ? scene.settings.bands : Sensor(SpectralBands::parse(bandsText));
    // Every render of this run: the bands, the density and the sampler.
    auto options = [&](int spp, std::optional<uint32_t> seed) {
      RenderOptions o;
      o.samples = spp;
      o.seed = seed;
      o.sampler = kind;
      o.stratifiedLanes = sampler == "stratified";
      o.bands = bands;
      o.wavelengthDensity =
          density == "visible" ? WavelengthDensity::Visible : WavelengthDensity::Sensor;
      return o;
    };
    SpectralImage ref;
    if (!referencePath.empty()) {
      ref = readSpectralExr(referencePath);
      if (ref.width != scene.settings.width || ref.height != scene.settings.height ||
          ref.xyz.empty() || ref.bands.toString() != bands.toString())
        throw nx::Error(referencePath +
                        ": does not match the scene's size and bands (or has no XYZ channels)");
    } else {
      // Seed 0x5eed: independent of the measured renders (the scene's seed).
      const RenderOptions o = options(referenceSpp, 0x5eed);
      std::fprintf(stderr, "nxbench: rendering the %d-spp reference...\n", referenceSpp);
      ref = toSpectralImage(render(scene, o).film);
    }
    std::printf("%6s %9s %12s %12s %11s %11s %13s %13s\n", "spp", "seconds", "samples/s", "rays/s",
                "RMSE(Y)", "relRMSE(Y)", "mean band rel", "max band rel");
    std::ofstream csv(csvPath);
    csv << "spp,seconds,samples_per_s,rays_per_s,rmse_Y,rel_rmse_Y";
    for (int b = 0; b < bands.count(); ++b) csv << ",rmse_" << bands.centroid(b) << "nm";
    csv << "\n";
    PlotSeries measured{"luminance (" + sampler + ")", {}, {}, 200, 40, 40, false};
    PlotSeries meanBand{"mean band", {}, {}, 40, 140, 40, false};
    PlotSeries worstBand{"worst band", {}, {}, 40, 60, 200, false};
    std::vector<double> logSpp, logErr;
    double lastRaysPerSecond = 0;
    for (int spp = 1; spp <= maxSpp; spp *= 2) {
      const RenderOutput out = render(scene, options(spp, std::nullopt));
      const bench::ImageErrors e = bench::compareWithReference(out.film, ref);
      const double sps = static_cast<double>(out.stats.samples) / out.stats.seconds;
      lastRaysPerSecond = static_cast<double>(out.stats.rays) / out.stats.seconds;
      std::printf("%6d %9.3f %12.4g %12.4g %11.5g %11.5g %13.5g %13.5g\n", spp, out.stats.seconds,
                  sps, lastRaysPerSecond, e.rmseY, e.relY, e.meanBandRel, e.maxBandRel);
      csv << spp << "," << out.stats.seconds << "," << sps << "," << lastRaysPerSecond << ","
          << e.rmseY << "," << e.relY;
      for (double r : e.bandRmse) csv << "," << r;
      csv << "\n";
      measured.x.push_back(out.stats.seconds);
      measured.y.push_back(e.relY);
      meanBand.x.push_back(out.stats.seconds);
      meanBand.y.push_back(e.meanBandRel);
      worstBand.x.push_back(out.stats.seconds);
      worstBand.y.push_back(e.maxBandRel);
      logSpp.push_back(std::log(spp));
      logErr.push_back(std::log(e.relY));
    }
    // Least-squares slope of log(error) against log(spp).
    double mx = 0, my = 0;
    for (size_t i = 0; i < logSpp.size(); ++i) mx += logSpp[i], my += logErr[i];
    mx /= static_cast<double>(logSpp.size()), my /= static_cast<double>(logSpp.size());
    double sxy = 0, sxx = 0;
    for (size_t i = 0; i < logSpp.size(); ++i)
      sxy += (logSpp[i] - mx) * (logErr[i] - my), sxx += (logSpp[i] - mx) * (logSpp[i] - mx);
    const double slope = sxx > 0 ? sxy / sxx : 0;
    std::printf("convergence slope of relRMSE(Y) against spp: %.3f (-0.5 for plain Monte Carlo)\n",
                slope);
    const double raw = rawRaysPerSecond(scene);
    std::printf("raw Embree closest-hit rays/s on this geometry: %.4g; path tracer at %d spp: %.4g "
                "rays/s = %.2f of raw\n",
                raw, maxSpp, lastRaysPerSecond, lastRaysPerSecond / raw);
    PlotSeries slopeLine{"slope -1/2 in spp", {}, {}, 90, 90, 200, true};
    if (!measured.x.empty()) {
      slopeLine.x = {measured.x.front(), measured.x.back()};
      slopeLine.y = {measured.y.front(),
                     measured.y.front() * std::sqrt(measured.x.front() / measured.x.back())};
    }
    writePreview(plotPath, 720, 480,
                 renderLogLogPlot({measured, meanBand, worstBand, slopeLine}, "render time (s)",
                                  "relative RMSE",
                                  std::filesystem::path(scenePath).filename().string() + ", " +
                                      density + " density",
                                  720, 480));
    std::fprintf(stderr, "nxbench: wrote %s and %s\n", csvPath.c_str(), plotPath.c_str());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "nxbench: error: %s\n", e.what());
    return 1;
  }
  return 0;
}
