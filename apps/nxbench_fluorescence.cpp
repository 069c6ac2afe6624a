// nxbench-fluorescence: what fluorescence costs.
//
//   nxbench-fluorescence [--threads N] [--spp N]
//
// 1. The thesis scene (Appendix A.6) with its two fluorescent spheres, and with their
//    fluorescence removed: time per sample.
// 2. A scene without fluorescent materials rendered by the plain path tracer and by the
//    fluorescence-capable one (the feature present but unused): time per sample.
// 3. Excitation guided by the light's spectrum against the matrix column alone, at equal spp
//    (--repeats seeds each): scenes/led_cards.scn (a fluorescent card beside a plain one under a
//    royal-blue LED: per-pixel relative noise of the fluorescent card in its emission bands,
//    520-570 nm, against the plain card's in the lamp's bands, 440-460 nm), and the broadband
//    thesis and lab_bench scenes (per-pixel relative noise over every lit pixel and band), with
//    time per sample.

#include <CLI/CLI.hpp>
#include <tbb/global_control.h>

#include <cmath>
#include <cstdio>
#include <functional>
#include <vector>

#include "apps/bench_util.h"
#include "apps/command_line.h"
#include "apps/seed_statistics.h"
#include "integrators/renderer.h"

namespace {

double nsPerSample(const nx::RenderScene& scene, int spp, bool force) {
  nx::RenderOptions o;
  o.samples = spp;
  o.forceFluorescencePath = force;
  const double s = nx::bench::fastestSeconds(3, [&] { nx::render(scene, o); });
  return s * 1e9 / (static_cast<double>(scene.settings.width) * scene.settings.height * spp);
}

using nx::bench::meanRelativeNoise;
using nx::bench::SeedStatistics;

// Renders of scene at spp, the excitation drawn as columnOnly says.
SeedStatistics seedStatistics(const nx::RenderScene& scene, int spp, bool columnOnly, int renders) {
  nx::RenderOptions o;
  o.samples = spp;
  o.columnOnlyExcitation = columnOnly;
  return nx::bench::seedStatistics(scene, o, renders);
}

// Band index whose centroid is nearest nm.
int bandNear(const SeedStatistics& s, double nm) {
  int best = 0;
  for (int b = 1; b < s.bands; ++b)
    if (std::abs(s.centroids[b] - nm) < std::abs(s.centroids[best] - nm)) best = b;
  return best;
}

// The LED cards: (fluorescent card's noise in 520-570 nm, plain card's in 440-460 nm). A pixel
// belongs to the fluorescent card where its 540 nm band is above half the image's largest, to
// the plain card where its 450 nm band is above half the largest and its 540 nm band below 1%
// of the fluorescent card's.
std::pair<double, double> ledCardNoise(const SeedStatistics& s) {
  const int dye = bandNear(s, 540), lamp = bandNear(s, 450);
  double dyeMax = 0, lampMax = 0;
  for (int y = 0; y < s.height; ++y)
    for (int x = 0; x < s.width; ++x) {
      dyeMax = std::max(dyeMax, s.mean(x, y, dye));
      lampMax = std::max(lampMax, s.mean(x, y, lamp));
    }
  const auto fluorescentCard = [&](int x, int y) { return s.mean(x, y, dye) > 0.5 * dyeMax; };
  const auto plainCard = [&](int x, int y) {
    return s.mean(x, y, lamp) > 0.5 * lampMax && s.mean(x, y, dye) < 0.01 * dyeMax;
  };
  const double fl = meanRelativeNoise(s, [&](int x, int y, int b) {
    return fluorescentCard(x, y) && s.centroids[b] >= 519 && s.centroids[b] <= 571;
  });
  const double plain = meanRelativeNoise(s, [&](int x, int y, int b) {
    return plainCard(x, y) && s.centroids[b] >= 439 && s.centroids[b] <= 461;
  });
  return {fl, plain};
}

} // namespace

int main(int argc, char** argv) {
  CLI::App app{"Time per sample with and without fluorescence"};
  int threads = 2, spp = 16, repeats = 8;
  app.add_option("--threads", threads, "Worker threads (default 2)")->check(nx::numberIn(1, 4096));
  app.add_option("--spp", spp, "Samples per pixel (default 16)")->check(nx::numberIn(1, 1 << 20));
  app.add_option("--repeats", repeats, "Seeds per noise measurement (default 8)")
      ->check(nx::numberIn(2, 1000));
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

    std::printf("\nexcitation strategy at %d spp, %d seeds: per-pixel relative noise\n", spp,
                repeats);
    const nx::RenderScene cards =
        nx::buildRenderScene(nx::loadScene(NX_SOURCE_DIR "/scenes/led_cards.scn"));
    std::printf("%-34s %10s %10s %8s %10s\n", "led_cards", "dye card", "plain card", "ratio",
                "ns/sample");
    for (const bool columnOnly : {true, false}) {
      const SeedStatistics st = seedStatistics(cards, spp, columnOnly, repeats);
      const auto [fl, plainNoise] = ledCardNoise(st);
      std::printf("%-34s %10.4f %10.4f %8.2f %10.0f\n",
                  columnOnly ? "  column alone" : "  guided by the light + MIS", fl, plainNoise,
                  fl / plainNoise, st.nsPerSample);
    }
    std::printf("%-34s %10s %10s\n", "broadband scenes", "noise", "ns/sample");
    for (const char* name : {"thesis", "lab_bench"}) {
      const nx::RenderScene scene = nx::buildRenderScene(
          nx::loadScene(std::string(NX_SOURCE_DIR "/scenes/") + name + ".scn"));
      for (const bool columnOnly : {true, false}) {
        const SeedStatistics st = seedStatistics(scene, spp, columnOnly, repeats);
        std::printf(
            "%-34s %10.4f %10.0f\n",
            (std::string(name) + (columnOnly ? ", column alone" : ", guided + MIS")).c_str(),
            nx::bench::litNoise(st), st.nsPerSample);
      }
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "nxbench-fluorescence: error: %s\n", e.what());
    return 1;
  }
  return 0;
}
