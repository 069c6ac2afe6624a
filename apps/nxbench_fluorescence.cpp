// nxbench-fluorescence: what fluorescence costs.
//
//   nxbench-fluorescence [--threads N] [--spp N]
//
// 1. The thesis scene (Appendix A.6) with its two fluorescent spheres, and with their
//    fluorescence removed: time per sample.
// 2. A scene without fluorescent materials rendered by the plain path tracer and by the
//    fluorescence-capable one (the feature present but unused): time per sample.

#include <CLI/CLI.hpp>
#include <tbb/global_control.h>

#include <cstdio>

#include "apps/bench_util.h"
#include "apps/command_line.h"
#include "integrators/renderer.h"

namespace {

double nsPerSample(const nx::RenderScene& scene, int spp, bool force) {
  nx::RenderOptions o;
  o.samples = spp;
  o.forceFluorescencePath = force;
  const double s = nx::bench::fastestSeconds(3, [&] { nx::render(scene, o); });
  return s * 1e9 / (static_cast<double>(scene.settings.width) * scene.settings.height * spp);
}

} // namespace

int main(int argc, char** argv) {
  CLI::App app{"Time per sample with and without fluorescence"};
  int threads = 2, spp = 16;
  app.add_option("--threads", threads, "Worker threads (default 2)")->check(nx::numberIn(1, 4096));
  app.add_option("--spp", spp, "Samples per pixel (default 16)")->check(nx::numberIn(1, 1 << 20));
  if (const int status = nx::parseCommandLine(app, argc, argv, "nxbench-fluorescence"); status >= 0)
    return status;
  try {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism,
                              static_cast<size_t>(threads));
    nx::SceneDesc thesis = nx::loadScene(NX_SOURCE_DIR "/scenes/thesis.scn");
    const nx::RenderScene withFl = nx::buildRenderScene(thesis);
    for (auto& o : thesis.objects) o.params.erase("fluorescence");
    const nx::RenderScene withoutFl = nx::buildRenderScene(thesis);
    const nx::RenderScene plain =
        nx::buildRenderScene(nx::loadScene(NX_SOURCE_DIR "/scenes/materials.scn"));

    std::printf("%-48s %12s\n", "scene (threads, spp)", "ns/sample");
    const double a = nsPerSample(withFl, spp, false), b = nsPerSample(withoutFl, spp, false);
    std::printf("%-48s %12.0f\n", "thesis A.6, fluorescent spheres", a);
    std::printf("%-48s %12.0f\n", "thesis A.6, fluorescence removed", b);
    std::printf("%-48s %11.1f%%\n", "  cost of fluorescence", 100 * (a / b - 1));
    const double c = nsPerSample(plain, spp, false), d = nsPerSample(plain, spp, true);
    std::printf("%-48s %12.0f\n", "materials (no fluorescence), plain path tracer", c);
    std::printf("%-48s %12.0f\n", "materials, fluorescence-capable path tracer", d);
    std::printf("%-48s %11.1f%%\n", "  cost of the feature present but unused", 100 * (d / c - 1));
  } catch (const std::exception& e) {
    std::fprintf(stderr, "nxbench-fluorescence: error: %s\n", e.what());
    return 1;
  }
  return 0;
}
