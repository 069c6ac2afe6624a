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
// Noise: the group given narrow LEDs, CIE A and F11, relit to each from relightable renders
// without targets, with that lamp as target and with all of them, against direct renders (RMS
// errors against a reference of 16x the samples), with relighting's own estimate.

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
#include "integrators/relight_targets.h"
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

// An LED: a Gaussian of `fwhm` nm around `peak`, tabulated every nm.
SpectrumDesc ledSpectrum(double peak, double fwhm) {
  SpectrumDesc s;
  s.kind = SpectrumDesc::Kind::Pairs;
  const double sigma = fwhm / 2.3548;
  for (int nm = 300; nm <= 1100; ++nm) {
    s.nm.push_back(nm);
    s.value.push_back(std::exp(-0.5 * (nm - peak) * (nm - peak) / (sigma * sigma)));
  }
  return s;
}

// The scene's group given the lamp `lamp` (a spectrum description).
SceneDesc withLamp(const SceneDesc& base, const std::string& group, const SpectrumDesc& lamp) {
  SceneDesc d = base;
  for (ObjectDesc& o : d.objects)
    if (o.emission && o.group == group) {
      const SourceLocation loc = o.emission->loc;
      *o.emission = lamp;
      o.emission->loc = loc;
    }
  return d;
}

// The noise of `img`: its squared error against `reference` (less the reference's own variance),
// relative to the reference's squared values, pooled over the pixels and bands (those with at
// least 5% of the brightest band's light in the reference); with `fluorescent`, only where
// fluoresced light is most of the pixel's band in the reference (which has its component
// layers), the bands' light counted there.
double relativeNoise(const SpectralImage& img, const SpectralImage& reference, bool fluorescent) {
  const int nb = reference.bands.count();
  const size_t n = reference.sampleCount.size();
  const auto inside = [&](size_t k) {
    return !fluorescent || reference.layers.at(1).values[k] > 0.5 * reference.radiance[k];
  };
  std::vector<double> light(static_cast<size_t>(nb), 0.0);
  for (size_t i = 0; i < n; ++i)
    for (int b = 0; b < nb; ++b)
      if (inside(i * nb + b)) light[b] += reference.radiance[i * nb + b];
  const double brightest = *std::max_element(light.begin(), light.end());
  double error = 0, signal = 0;
  for (size_t i = 0; i < n; ++i)
    for (int b = 0; b < nb; ++b) {
      const size_t k = i * nb + b;
      if (light[b] < 0.05 * brightest || !inside(k)) continue;
      const double d = img.radiance[k] - reference.radiance[k];
      error += d * d - reference.bandVariance[k];
      signal += reference.radiance[k] * reference.radiance[k];
    }
  return signal > 0 ? std::sqrt(std::max(error, 0.0) / signal) : 0.0;
}

// Noise of relit images against direct renders at equal samples: the group given each lamp
// directly, and relit to it from a relightable render without targets, told that lamp as its
// target, and told all the lamps at once (each then relit in turn).
void noiseAgainstDirect(const SceneDesc& base, int width, const std::string& group,
                        const RenderOptions& options) {
  const std::vector<std::pair<std::string, SpectrumDesc>> lamps = [] {
    SpectrumDesc a, f11;
    a.kind = f11.kind = SpectrumDesc::Kind::Name;
    a.name = "A";
    f11.name = "F11";
    return std::vector<std::pair<std::string, SpectrumDesc>>{{"LED 450/20", ledSpectrum(450, 20)},
                                                             {"LED 520/30", ledSpectrum(520, 30)},
                                                             {"CIE A", a},
                                                             {"F11", f11}};
  }();
  const SceneDesc scaled = variant(base, width, group, "");
  // Each lamp's spectrum as its emitters are written with it (a target for the render).
  std::vector<Spectrum> written;
  for (const auto& [name, lamp] : lamps) {
    SceneDesc d = withLamp(scaled, group, lamp);
    d.relightable = true;
    const RenderScene s = buildRenderScene(d);
    for (size_t k = 0; k < s.relight.ofSource.size(); ++k)
      if (s.lightGroups.names[s.relight.groupOfSource[k]] == group)
        written.push_back(s.relight.ofSource[k]);
  }
  RenderOptions direct = options, relightable = options, reference = options;
  direct.seed = 11;
  relightable.seed = 12;
  reference.seed = 13;
  reference.samples = 16 * options.samples;
  reference.components = true;
  const auto relit = [&](const std::vector<RelightTargetDesc>& targets, size_t lamp) {
    SceneDesc d = scaled;
    d.relightable = true;
    d.relightTargets = targets;
    const RenderScene scene = buildRenderScene(d);
    const SpectralImage img = toSpectralImage(render(scene, relightable).film);
    std::vector<std::string> warnings;
    const GroupSpectrum g =
        groupSpectrum(img, group, written[lamp], 300, 1100, lamps[lamp].first, warnings);
    return std::make_pair(relightImage(img, {g}),
                          relitNoiseFactor(img, relightSourcesOf(img, group), g.binned));
  };
  std::printf("\nnoise: group '%s' relit to each lamp, against a direct render under it at equal "
              "samples: ratio of RMS errors against a reference of 16x the samples, relative, in "
              "the pixels and bands where fluoresced light is most of the light (whole image in "
              "brackets)\n%-12s %16s %9s %16s %16s\n",
              group.c_str(), "lamp", "no targets", "estimate", "this target", "all targets");
  std::vector<RelightTargetDesc> all;
  for (size_t k = 0; k < lamps.size(); ++k) all.push_back({group, written[k], lamps[k].first});
  for (size_t k = 0; k < lamps.size(); ++k) {
    const RenderScene scene = buildRenderScene(withLamp(scaled, group, lamps[k].second));
    const SpectralImage d = toSpectralImage(render(scene, direct).film);
    const SpectralImage ref = toSpectralImage(render(scene, reference).film);
    const auto [plain, estimate] = relit({}, k);
    const SpectralImage one = relit({{group, written[k], lamps[k].first}}, k).first;
    const SpectralImage every = relit(all, k).first;
    const auto column = [&](const SpectralImage& r) {
      char fluorescent[16] = "     -", text[64];
      if (const double noise = relativeNoise(d, ref, true); noise > 0) // none: nothing fluoresces
        std::snprintf(fluorescent, sizeof fluorescent, "%6.2f",
                      relativeNoise(r, ref, true) / noise);
      std::snprintf(text, sizeof text, "%s (%5.2f)", fluorescent,
                    relativeNoise(r, ref, false) / relativeNoise(d, ref, false));
      return std::string(text);
    };
    std::printf("%-12s %16s %9.2f %16s %16s\n", lamps[k].first.c_str(), column(plain).c_str(),
                estimate.factor, column(one).c_str(), column(every).c_str());
  }
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
  noiseAgainstDirect(base, width, group, options);
  return 0;
}

} // namespace

int main(int argc, char** argv) {
  return mainReportingErrors("nxbench-relight", run, argc, argv);
}
