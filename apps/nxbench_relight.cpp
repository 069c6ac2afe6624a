// nxbench-relight: what a relightable render costs and how close relighting comes.
//
//   nxbench-relight [scene.scn] [--group NAME] [--spp N] [--width W] [--threads N]
//
// Cost: a plain render against relightable ones on excitation grids of 10, 5 and 1 nm: render
// seconds (fastest of repeats), transport entries per light group, bytes per pixel of the film
// and of the EXR (uncompressed, and zip as nxrender writes it).
// Approximation: the group's emitters given each lamp spectrum in turn (CIE A, D65, F2, F11 and
// a white LED), rendered relightable and relit to their own spectrum. Per sample the two differ
// only by S(mu) against the bin average of S, so the mean over pixels of (relit - render) per
// band is the grid's error, measured with a paired standard error; printed as the worst and the
// mean relative error over the bands.

#include <CLI/CLI.hpp>
#include <tbb/global_control.h>

#include <cmath>
#include <cstdio>
#include <filesystem>

#include "apps/bench_util.h"
#include "apps/command_line.h"
#include "apps/program_main.h"
#include "core/error.h"
#include "integrators/relight_image.h"
#include "integrators/renderer.h"
#include "integrators/scene_reader.h"
#include "io/spectral_exr.h"

namespace {

using namespace nx;

// The scene at `width` pixels across (the aspect kept), its group's emitters given `lamp`.
SceneDesc variant(const SceneDesc& base, int width, const std::string& group,
                  const std::string& lamp) {
  SceneDesc d = base;
  d.settings.height = std::max(1, d.settings.height * width / d.settings.width);
  d.settings.width = width;
  if (!lamp.empty())
    for (ObjectDesc& o : d.objects)
      if (o.emission && o.group == group) {
        o.emission->kind = SpectrumDesc::Kind::Name;
        o.emission->name = lamp;
      }
  return d;
}

int run(int argc, char** argv) {
  CLI::App app{"nxbench-relight: cost and grid error of relightable renders"};
  std::string scenePath = std::string(NX_SOURCE_DIR) + "/scenes/lab_bench.scn", group = "led";
  int spp = 64, width = 80, threads = 2;
  app.add_option("scene", scenePath, "Scene file (default: scenes/lab_bench.scn)");
  app.add_option("--group", group, "The light group whose lamp spectrum is varied (default led)");
  app.add_option("--spp", spp, "Samples per pixel (default 64)")->check(numberIn(1, 1 << 20));
  app.add_option("--width", width, "Image width in pixels (default 80)")->check(numberIn(8, 4096));
  app.add_option("--threads", threads, "Worker threads (default 2)")->check(numberIn(1, 4096));
  if (const int status = parseCommandLine(app, argc, argv, "nxbench-relight"); status >= 0)
    return status;
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism,
                            static_cast<size_t>(threads));
  const SceneDesc base = loadScene(scenePath);
  RenderOptions options;
  options.samples = spp;

  const SceneDesc plainDesc = variant(base, width, group, "");
  const RenderScene plain = buildRenderScene(plainDesc);
  const double pixels = static_cast<double>(plain.settings.width) * plain.settings.height;
  std::printf("%s at %dx%d, %d spp, %d threads\n\n", scenePath.c_str(), plain.settings.width,
              plain.settings.height, spp, threads);
  std::printf("%-14s %9s %7s %9s %12s %12s %12s\n", "render", "seconds", "x plain", "entries",
              "film B/px", "EXR B/px", "zip B/px");
  const double t0 = bench::fastestSeconds(3, [&] { render(plain, options); });
  std::printf("%-14s %9.3f %7.2f %9s %12s %12s %12s\n", "plain", t0, 1.0, "-", "-", "-", "-");
  for (double step : {10.0, 5.0, 1.0}) {
    SceneDesc d = plainDesc;
    d.relightable = true;
    const RenderScene scene = buildRenderScene(d);
    RenderOptions o = options;
    o.relightStepNm = step;
    std::optional<RenderOutput> out;
    const double t = bench::fastestSeconds(2, [&] { out.emplace(render(scene, o)); });
    const SpectralImage img = toSpectralImage(out->film);
    const double planes = static_cast<double>(img.relight.sources.size() * img.relight.size());
    const std::string path =
        (std::filesystem::temp_directory_path() / "nxbench_relight.exr").string();
    ExrEncoding zip;
    zip.compression = ExrCompression::Zip;
    writeSpectralExr(path, img, zip);
    const double zipBytes = static_cast<double>(std::filesystem::file_size(path));
    std::filesystem::remove(path);
    char name[32];
    std::snprintf(name, sizeof name, "relight %g nm", step);
    std::printf("%-14s %9.3f %7.2f %9zu %12.0f %12.0f %12.0f\n", name, t, t / t0,
                img.relight.size(), planes * 2 * 4, planes * 2 * 4, zipBytes / pixels);
  }

  std::printf("\ngrid error: group '%s' relit to its own lamp spectrum, relative to each band's "
              "mean\n%-10s %6s %12s %12s %10s\n",
              group.c_str(), "lamp", "step nm", "worst band", "mean band", "worst z");
  for (const char* lamp : {"A", "D65", "F2", "F11", "led"}) {
    for (double step : {10.0, 5.0, 1.0}) {
      SceneDesc d = variant(base, width, group, lamp);
      d.relightable = true;
      const RenderScene scene = buildRenderScene(d);
      RenderOptions o = options;
      o.relightStepNm = step;
      const SpectralImage img = toSpectralImage(render(scene, o).film);
      const SpectralImage relit = relightImage(img, {});
      const int nb = img.bands.count();
      double worst = 0, sum = 0, worstZ = 0;
      int counted = 0;
      for (int b = 0; b < nb; ++b) {
        double mean = 0, diff = 0, diff2 = 0;
        const size_t n = img.sampleCount.size();
        for (size_t i = 0; i < n; ++i) {
          const double r = img.radiance[i * nb + b], e = relit.radiance[i * nb + b] - r;
          mean += r, diff += e, diff2 += e * e;
        }
        mean /= static_cast<double>(n);
        diff /= static_cast<double>(n);
        const double se = std::sqrt(std::max(0.0, diff2 / static_cast<double>(n) - diff * diff) /
                                    (static_cast<double>(n) - 1.0));
        if (!(mean > 0)) continue;
        const double rel = std::abs(diff) / mean;
        if (rel > worst) worst = rel, worstZ = se > 0 ? std::abs(diff) / se : 0;
        sum += rel;
        ++counted;
      }
      std::printf("%-10s %6g %11.3f%% %11.3f%% %10.1f\n", lamp, step, 100 * worst,
                  100 * sum / std::max(counted, 1), worstZ);
    }
  }
  return 0;
}

} // namespace

int main(int argc, char** argv) {
  return mainReportingErrors("nxbench-relight", run, argc, argv);
}
