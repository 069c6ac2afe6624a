// nxrelight: a relightable render (nxrender --relightable) under new emission spectra.
//
//   nxrelight IN.exr --light GROUP=spectrum.csv|NAME [--light GROUP=...] -o OUT.exr
//
// Each --light replaces the emission spectrum of a light group's emitters (their scale= and
// measuring geometry still apply); the other groups keep the spectra they were rendered with.
// Writes an ordinary spectral image (the channels of a render, with variances) and its preview
// OUT.png. Method and approximation: docs/relighting.md.

#include <CLI/CLI.hpp>

#include <cstdio>
#include <filesystem>

#include "apps/command_line.h"
#include "apps/program_main.h"
#include "core/error.h"
#include "core/input_files.h"
#include "integrators/relight_image.h"
#include "integrators/renderer.h"
#include "io/atomic_file.h"
#include "io/preview_image.h"
#include "io/spectral_exr.h"
#include "spectra/colour.h"

namespace {

int run(int argc, char** argv) {
  CLI::App app{"nxrelight: renders a relightable image (nxrender --relightable) under new "
               "emission spectra of its light groups"};
  std::string input, output;
  std::vector<std::string> lights;
  app.add_option("input", input, "A relightable spectral EXR written by nxrender --relightable")
      ->required();
  app.add_option("--light", lights,
                 "GROUP=spectrum.csv: the new emission spectrum (two columns nm,value; or a "
                 "built-in name: A, D65, F11, blackbody:3000, ...) of light group GROUP's "
                 "emitters, their scale= still applying; repeatable (groups not given keep their "
                 "rendered spectra)");
  app.add_option("-o,--output", output, "Relit spectral EXR (its preview goes beside it as .png)")
      ->required();
  if (const int status = nx::parseCommandLine(app, argc, argv, "nxrelight"); status >= 0)
    return status;
  // The inputs first: no output may replace one (core/input_files.h).
  nx::noteInputFile(input);
  for (const std::string& l : lights)
    if (const size_t eq = l.find('='); eq != std::string::npos) nx::noteInputFile(l.substr(eq + 1));
  nx::checkExrOutputName(output);
  const std::string preview = std::filesystem::path(output).replace_extension(".png").string();
  nx::checkWritable(output);
  nx::checkWritable(preview);
  const nx::SpectralImage image = nx::readSpectralExr(input);
  if (!image.relight.present())
    throw nx::Error(input + ": expected a relightable image (rendered with --relightable), "
                            "found one without relight channels");
  std::vector<nx::GroupSpectrum> spectra;
  std::vector<std::string> warnings;
  for (const std::string& l : lights) {
    const size_t eq = l.find('=');
    if (eq == std::string::npos || eq == 0 || eq + 1 == l.size())
      throw nx::Error("--light: expected GROUP=spectrum.csv (or GROUP=NAME, a built-in emission "
                      "such as D65), found '" +
                      l + "'");
    try {
      spectra.push_back(
          nx::groupSpectrumFromText(image, l.substr(0, eq), l.substr(eq + 1), warnings));
    } catch (const nx::Error& e) {
      throw nx::Error("--light " + l + ": " + e.what());
    }
  }
  for (const std::string& w : warnings) std::fprintf(stderr, "nxrelight: %s\n", w.c_str());
  const nx::SpectralImage relit = nx::relightImage(image, spectra);
  {
    const nx::OutputLock lock(output); // the EXR and its preview as one pair
    nx::AtomicFileGroup pair;
    nx::writeSpectralExr(output, relit);
    nx::writePreview(preview, relit.width, relit.height, nx::previewPixels(relit));
    pair.commit();
  }
  std::fprintf(stderr, "nxrelight: wrote %s and %s (%dx%d, %zu light group%s relit)\n",
               output.c_str(), preview.c_str(), relit.width, relit.height, spectra.size(),
               spectra.size() == 1 ? "" : "s");
  return 0;
}

} // namespace

int main(int argc, char** argv) {
  return nx::mainReportingErrors("nxrelight", run, argc, argv);
}
