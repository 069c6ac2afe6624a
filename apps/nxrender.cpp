// nxrender: renders a scene file to a spectral OpenEXR and a tone-mapped preview.

#include <CLI/CLI.hpp>
#include <tbb/global_control.h>
#include <tbb/info.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <string>

#include "core/error.h"
#include "integrators/renderer.h"
#include "io/atomic_file.h"
#include "io/preview_image.h"
#include "io/spectral_exr.h"

namespace {

std::string replaceExtension(const std::string& path, const std::string& ext) {
  return std::filesystem::path(path).replace_extension(ext).string();
}

const char* modeName(nx::RenderMode m) {
  return m == nx::RenderMode::Rt ? "rt" : m == nx::RenderMode::Mcpt ? "mcpt" : "spectral_mcpt";
}

// Progress on stderr: a live bar on a terminal, a plain line every few seconds otherwise.
class Progress {
public:
  Progress() : tty_(isatty(STDERR_FILENO) == 1), start_(std::chrono::steady_clock::now()) {}
  void update(int done, int total) {
    const double elapsed = seconds();
    const double fraction = static_cast<double>(done) / total;
    const double eta = fraction > 0 ? elapsed * (1 - fraction) / fraction : 0;
    if (tty_) {
      if (elapsed - last_ < 0.1 && done != total) return;
      const int width = 40, filled = static_cast<int>(fraction * width);
      std::fprintf(stderr, "\r[%s%s] %3.0f%%  %.1f s elapsed, ETA %.1f s ",
                   std::string(filled, '=').c_str(), std::string(width - filled, ' ').c_str(),
                   100 * fraction, elapsed, eta);
      if (done == total) std::fprintf(stderr, "\n");
    } else {
      if (elapsed - last_ < 5.0) return;
      std::fprintf(stderr, "nxrender: %.0f%% done, %.1f s elapsed, ETA %.1f s\n", 100 * fraction,
                   elapsed, eta);
    }
    last_ = elapsed;
  }

private:
  double seconds() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  }
  bool tty_;
  std::chrono::steady_clock::time_point start_;
  double last_ = 0;
};

int run(int argc, char** argv) {
  CLI::App app{
      "nxrender: spectral path tracer for fluorescence research\n"
      "Renders SCENE to a spectral OpenEXR (Fichet et al. 2021 layout) and a tone-mapped preview."};
  app.set_version_flag("--version", std::string("nxrender ") + NX_VERSION);
  int threads = 0, spp = 0;
  long long seed = -1;
  std::string output, bandsText, lightSampling = "mis", sampler = "sobol", scenePath;
  bool noFluorescence = false;
  app.add_option("--threads", threads, "Worker threads (default: all cores)")
      ->check(CLI::Range(1, 4096));
  app.add_option("--spp", spp, "Samples per pixel (default: the scene's <sampl>)")
      ->check(CLI::Range(1, 1 << 30));
  app.add_option("-o,--output", output,
                 "Spectral EXR to write; the preview goes beside it as .png "
                 "(default: the preview at the scene's <path>, the EXR beside it)");
  app.add_option("--bands", bandsText,
                 "Output bands START:END:STEP in nm (default: the scene's, else 400:700:10)");
  app.add_option("--seed", seed, "Random seed (default: the scene's <seed>, else 0)")
      ->check(CLI::Range(0LL, 2147483647LL));
  app.add_option("--light-sampling", lightSampling,
                 "mis (default), bsdf or nee: how diffuse surfaces find lights")
      ->check(CLI::IsMember({"mis", "bsdf", "nee"}));
  app.add_option("--sampler", sampler, "sobol (Owen-scrambled, default) or independent")
      ->check(CLI::IsMember({"sobol", "independent"}));
  app.add_flag("--no-fluorescence", noFluorescence,
               "Render fluorescent materials as their ordinary reflectance (for comparisons)");
  app.add_option("scene", scenePath, "Scene file (.scn)")->required();
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  }

  nx::SceneDesc desc = nx::loadScene(scenePath);
  for (const auto& w : desc.warnings) std::fprintf(stderr, "%s\n", w.c_str());
  if (noFluorescence)
    for (auto& o : desc.objects) o.fluorescence.reset();
  const nx::RenderScene scene = nx::buildRenderScene(desc);

  nx::RenderOptions options;
  options.samples = spp;
  if (seed >= 0) options.seed = static_cast<uint32_t>(seed);
  if (!bandsText.empty()) options.bands = nx::SpectralBands::parse(bandsText);
  options.lightSampling = lightSampling == "bsdf"  ? nx::LightSampling::BsdfOnly
                          : lightSampling == "nee" ? nx::LightSampling::NeeOnly
                                                   : nx::LightSampling::Mis;
  options.sampler =
      sampler == "independent" ? nx::SamplerKind::Independent : nx::SamplerKind::SobolOwen;

  std::string exrPath, previewPath;
  if (!output.empty()) {
    if (std::filesystem::path(output).extension() != ".exr")
      throw nx::Error(output + ": expected an output file name ending in .exr");
    exrPath = output;
    previewPath = replaceExtension(output, ".png");
  } else {
    previewPath = scene.settings.outputPath.empty()
                      ? std::filesystem::path(scenePath).stem().string() + ".png"
                      : scene.settings.outputPath;
    if (!nx::isPreviewPath(previewPath))
      throw nx::Error(desc.settings.loc.str() +
                      ": expected a <path> ending in .png or .bmp, found '" + previewPath + "'");
    exrPath = replaceExtension(previewPath, ".exr");
  }
  nx::checkWritable(exrPath);
  nx::checkWritable(previewPath);

  const int nThreads = threads > 0 ? threads : tbb::info::default_concurrency();
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism,
                            static_cast<size_t>(nThreads));
  Progress progress;
  options.progress = [&](int done, int total) { progress.update(done, total); };
  const nx::RenderOutput result = nx::render(scene, options);

  nx::SpectralImage image = nx::toSpectralImage(result.film);
  image.attributes["nxrender.version"] = NX_VERSION;
  image.attributes["nxrender.scene"] = scenePath;
  image.attributes["nxrender.mode"] = modeName(scene.settings.mode);
  image.attributes["nxrender.samplesPerPixel"] = std::to_string(result.samplesPerPixel);
  image.attributes["nxrender.seed"] = std::to_string(result.seed);
  image.attributes["nxrender.bands"] = result.film.bands().toString();
  image.attributes["nxrender.sampler"] = sampler;
  image.attributes["nxrender.lightSampling"] = lightSampling;
  image.attributes["nxrender.renderSeconds"] = std::to_string(result.stats.seconds);
  image.attributes["nxrender.fluorescence"] = scene.hasFluorescence ? "on" : "off";
  nx::writeSpectralExr(exrPath, image);
  nx::writePreview(previewPath, image.width, image.height,
                   nx::previewPixels(result.film, scene.previewWhite));

  const double s = result.stats.seconds;
  std::fprintf(stderr,
               "nxrender: %dx%d, %d spp, %s, %d threads: %.2f s, %.3g samples/s, %.3g rays/s; "
               "wrote %s and %s\n",
               image.width, image.height, result.samplesPerPixel, modeName(scene.settings.mode),
               nThreads, s, static_cast<double>(result.stats.samples) / s,
               static_cast<double>(result.stats.rays) / s, exrPath.c_str(), previewPath.c_str());
  if (result.stats.nonFinite > 0)
    std::fprintf(stderr,
                 "nxrender: warning: %llu samples with a NaN or infinite value were dropped\n",
                 static_cast<unsigned long long>(result.stats.nonFinite));
  return 0;
}

} // namespace

int main(int argc, char** argv) {
  try {
    return run(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "nxrender: error: %s\n", e.what());
    return 1;
  }
}
