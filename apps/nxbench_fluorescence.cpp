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
// 4. The plain card under a lamp whose spectrum is the dye card's emission (its 5 nm bin
//    values): the plain card's noise in 520-570 nm against the dye card's in the same bands.
//    The two spectra then have the same shape, so whatever the dye card adds is the excitation
//    sampling's own noise (a steep emission spectrum is noisier per band than the lamp's
//    smooth peak whatever the excitation strategy: wavelengths fall unevenly into a band).

#include <CLI/CLI.hpp>
#include <tbb/global_control.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <regex>
#include <stdexcept>
#include <string>
#include <vector>

#include "apps/bench_util.h"
#include "apps/command_line.h"
#include "apps/seed_statistics.h"
#include "core/file_text.h"
#include "integrators/renderer.h"
#include "integrators/scene_reader.h"

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

// Which pixels of the LED cards' render hold which card: the fluorescent card where its 540 nm
// band is above half the image's largest, the plain card where its 450 nm band is above half
// the largest and its 540 nm band below 1% of the fluorescent card's.
struct CardPixels {
  std::function<bool(int, int)> fluorescent, plain;
};
CardPixels cardPixels(const SeedStatistics& s) {
  const int dye = bandNear(s, 540), lamp = bandNear(s, 450);
  double dyeMax = 0, lampMax = 0;
  for (int y = 0; y < s.height; ++y)
    for (int x = 0; x < s.width; ++x) {
      dyeMax = std::max(dyeMax, s.mean(x, y, dye));
      lampMax = std::max(lampMax, s.mean(x, y, lamp));
    }
  return {[&s, dye, dyeMax](int x, int y) { return s.mean(x, y, dye) > 0.5 * dyeMax; },
          [&s, dye, lamp, dyeMax, lampMax](int x, int y) {
            return s.mean(x, y, lamp) > 0.5 * lampMax && s.mean(x, y, dye) < 0.01 * dyeMax;
          }};
}

// Relative noise of `s` over the pixels where `card` holds, in the bands within [lo, hi] nm.
double noiseOver(const SeedStatistics& s, const std::function<bool(int, int)>& card, double lo,
                 double hi) {
  return meanRelativeNoise(s, [&](int x, int y, int b) {
    return card(x, y) && s.centroids[b] >= lo && s.centroids[b] <= hi;
  });
}

// The LED cards: (fluorescent card's noise in 520-570 nm, plain card's in 440-460 nm).
std::pair<double, double> ledCardNoise(const SeedStatistics& s) {
  const CardPixels cards = cardPixels(s);
  return {noiseOver(s, cards.fluorescent, 519, 571), noiseOver(s, cards.plain, 439, 461)};
}

// The dye card's emitted spectrum under the cards' lamp, per 5 nm bin of the matrix: Z(o) =
// sum over excitation bins i of M[i][o] times the lamp's mean over bin i (the emission's shape;
// the elastic part is 0 where the lamp is dark, above 480 nm).
std::vector<double> dyeEmission(const nx::RenderScene& cards) {
  using RM = nx::ReradiationMatrix;
  const RM* m = nullptr;
  for (const nx::Material& material : cards.materials)
    if (material.reradiation) m = material.reradiation.get();
  const nx::Spectrum* lamp = nullptr;
  for (const nx::Spectrum& e : cards.emission)
    if (e(450) > 0) lamp = &e;
  if (!m || !lamp) throw std::runtime_error("led_cards: expected a dye and a blue lamp");
  const nx::ExcitationGuide guide = nx::excitationGuideOf(lamp);
  std::vector<double> z(RM::kBins, 0.0);
  for (int o = 0; o < RM::kBins; ++o)
    for (int i = 0; i < o; ++i)
      z[static_cast<size_t>(o)] += (*m)(i, o) * guide.mean[static_cast<size_t>(i)];
  return z;
}

// The cards' scene with the lamp's spectrum replaced by the dye card's emission above 485 nm (a
// table stepping at the matrix's bin ends) and the dye removed.
nx::RenderScene matchedLampScene(const nx::RenderScene& cards, const std::string& path) {
  using RM = nx::ReradiationMatrix;
  const std::vector<double> z = dyeEmission(cards);
  double peak = 0;
  for (double v : z) peak = std::max(peak, v);
  std::string table;
  for (int o = RM::binOf(487.5); o < RM::binOf(717.5); ++o) {
    const double lo = RM::kMinNm + o * RM::kBinNm, v = z[static_cast<size_t>(o)] / peak;
    table += (table.empty() ? "" : ", ") + std::to_string(lo + 0.01) + ":" + std::to_string(v) +
             ", " + std::to_string(lo + RM::kBinNm - 0.01) + ":" + std::to_string(v);
  }
  const std::string original = nx::readRegularFile(path, 64u << 20, "scene file");
  std::string text =
      std::regex_replace(original, std::regex("<emission scale=\"4\">[^<]*</emission>"),
                         "<emission scale=\"0.2\">" + table + "</emission>");
  if (text == original)
    throw std::runtime_error(path + ": expected the lamp's <emission scale=\"4\"> to replace");
  text = std::regex_replace(text, std::regex("<fluorescence>.*</fluorescence>"), "");
  return nx::buildRenderScene(nx::parseScene(text, path));
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
    const std::string cardsPath = NX_SOURCE_DIR "/scenes/led_cards.scn";
    const nx::RenderScene cards = nx::buildRenderScene(nx::loadScene(cardsPath));
    std::printf("%-34s %10s %10s %8s %10s\n", "led_cards", "dye card", "plain card", "ratio",
                "ns/sample");
    SeedStatistics guided;
    for (const bool columnOnly : {true, false}) {
      const SeedStatistics st = seedStatistics(cards, spp, columnOnly, repeats);
      const auto [fl, plainNoise] = ledCardNoise(st);
      std::printf("%-34s %10.4f %10.4f %8.2f %10.0f\n",
                  columnOnly ? "  column alone" : "  guided by the light + MIS", fl, plainNoise,
                  fl / plainNoise, st.nsPerSample);
      if (!columnOnly) guided = st;
    }
    // The same spectral shape on both cards: the plain card under the dye's emission.
    const SeedStatistics matched =
        seedStatistics(matchedLampScene(cards, cardsPath), spp, false, repeats);
    const CardPixels pixels = cardPixels(guided);
    const double dyeNoise = noiseOver(guided, pixels.fluorescent, 519, 571);
    const double matchedNoise = noiseOver(matched, pixels.plain, 519, 571);
    std::printf("%-34s %10.4f %10.4f %8.2f\n", "  plain card, lamp = dye's emission", dyeNoise,
                matchedNoise, dyeNoise / matchedNoise);
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
