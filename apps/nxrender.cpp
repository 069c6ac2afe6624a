// nxrender: the command-line renderer.
//
// Until the path tracer lands, it loads and builds the scene (reporting its errors) and writes
// the spectral test chart (see spectral_chart.h) so that the whole output path can be used.

#include <CLI/CLI.hpp>
#include <tbb/global_control.h>
#include <tbb/info.h>

#include <chrono>
#include <cstdio>
#include <string>

#include "apps/spectral_chart.h"
#include "core/error.h"
#include "integrators/render_scene.h"
#include "io/atomic_file.h"
#include "io/preview_image.h"
#include "io/spectral_exr.h"
#include "spectra/tonemap.h"

namespace {

std::string replaceExtension(const std::string& path, const std::string& ext) {
  const auto dot = path.find_last_of('.');
  const auto slash = path.find_last_of('/');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return path + ext;
  return path.substr(0, dot) + ext;
}

int run(int argc, char** argv) {
  CLI::App app{"nxrender: spectral path tracer for fluorescence research"};
  app.set_version_flag("--version", std::string("nxrender ") + NX_VERSION);
  int threads = 0;
  std::string output = "chart.exr";
  std::string bandsText;
  std::string scene;
  app.add_option("--threads", threads, "Worker threads (default: all cores)")
      ->check(CLI::Range(1, 4096));
  app.add_option("-o,--output", output,
                 "Spectral EXR to write; the preview goes beside it as .png");
  app.add_option("--bands", bandsText, "Output bands START:END:STEP in nm (default: the scene's, else 400:700:10)");
  app.add_option("scene", scene, "Scene file (.scn)")->required();
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  }

  const nx::SceneDesc desc = nx::loadScene(scene);
  for (const auto& w : desc.warnings) std::fprintf(stderr, "%s\n", w.c_str());
  const nx::RenderScene renderScene = nx::buildRenderScene(desc);
  const nx::SpectralBands bands = bandsText.empty() ? renderScene.settings.bands : nx::SpectralBands::parse(bandsText);
  if (output.size() < 4 || output.substr(output.size() - 4) != ".exr")
    throw nx::Error(output + ": expected an output file name ending in .exr");
  const std::string preview = replaceExtension(output, ".png");
  nx::checkWritable(output);
  nx::checkWritable(preview);

  const int nThreads = threads > 0 ? threads : tbb::info::default_concurrency();
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism,
                            static_cast<size_t>(nThreads));

  std::fprintf(stderr,
               "nxrender: scene rendering is not implemented yet; writing the spectral test "
               "chart (%d bands %s) instead\n",
               bands.count(), bands.toString().c_str());
  const auto start = std::chrono::steady_clock::now();
  nx::SpectralImage image = nx::renderSpectralChart(bands, 32);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  image.attributes["nxrender.version"] = NX_VERSION;
  image.attributes["nxrender.scene"] = scene;
  image.attributes["nxrender.bands"] = bands.toString();
  image.attributes["nxrender.renderSeconds"] = std::to_string(seconds);

  std::vector<nx::Rgb> rgb(static_cast<size_t>(image.width) * image.height);
  for (size_t i = 0; i < rgb.size(); ++i)
    rgb[i] = {image.rgb[3 * i], image.rgb[3 * i + 1], image.rgb[3 * i + 2]};
  nx::writeSpectralExr(output, image);
  nx::writePreview(preview, image.width, image.height, nx::tonemapReinhard(rgb, {}));
  std::fprintf(stderr, "nxrender: wrote %s and %s (%dx%d, %.2f s, %d threads)\n", output.c_str(),
               preview.c_str(), image.width, image.height, seconds, nThreads);
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
