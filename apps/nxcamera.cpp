// nxcamera: the digital numbers a camera would record of a render (a synthetic capture).
//
//   nxcamera RENDER.exr -o CAPTURE.exr [--envi CAPTURE.img] [--f-number N] [--transmittance T]
//            [--irradiance-scale K] [--exposure S] [--pitch UM] [--qe Q[,Q...]]
//            [--full-well E] [--read-noise E] [--dark-current E] [--gain K] [--offset DN]
//            [--bits B] [--seed S]
//
// Radiance -> irradiance at the sensor -> photo-electrons (shot noise, dark current, full
// well) -> read noise -> DN (gain, offset, bit depth); see docs/compare.md. A separate program
// because it post-processes any render (or merged farm job) and needs none of the renderer.

#include <CLI/CLI.hpp>

#include <cstdio>
#include <sstream>

#include "apps/command_line.h"
#include "core/error.h"
#include "core/input_files.h"
#include "core/text_table.h"
#include "io/atomic_file.h"
#include "io/envi_export.h"
#include "io/spectral_exr.h"
#include "spectra/camera_simulation.h"

int main(int argc, char** argv) {
  CLI::App app{"nxcamera: what a camera would record of a render"};
  std::string input, output, envi, qe = "0.6";
  nx::CameraModel cam;
  app.add_option("render", input, "The render (spectral EXR)")->required();
  app.add_option("-o,--output", output, "The synthetic capture (spectral EXR of DN)")->required();
  app.add_option("--envi", envi, "Also an ENVI cube of the DN (data file name, e.g. capture.img)");
  app.add_option("--f-number", cam.fNumber, "Lens f-number N (irradiance = pi T L / 4 N^2)");
  app.add_option("--transmittance", cam.lensTransmittance, "Lens transmittance T");
  app.add_option("--irradiance-scale", cam.irradianceScale,
                 "Irradiance per unit radiance instead of the lens formula (sr)");
  app.add_option("--exposure", cam.exposureSeconds, "Exposure time (s)");
  app.add_option("--pitch", cam.pixelPitchUm, "Pixel pitch (um)");
  app.add_option("--qe", qe, "Quantum efficiency: one value or one per band, comma-separated");
  app.add_option("--full-well", cam.fullWellElectrons, "Full-well capacity (electrons)");
  app.add_option("--read-noise", cam.readNoiseElectrons,
                 "Read noise (electrons, standard deviation)");
  app.add_option("--dark-current", cam.darkCurrentElectrons, "Dark current (electrons per second)");
  app.add_option("--gain", cam.gainDnPerElectron, "System gain K (DN per electron)");
  app.add_option("--offset", cam.offsetDn, "Black level (DN)");
  app.add_option("--bits", cam.bitDepth, "ADC bit depth");
  app.add_option("--seed", cam.seed, "Seed of the noise");
  if (const int status = nx::parseCommandLine(app, argc, argv, "nxcamera"); status >= 0)
    return status;
  try {
    cam.quantumEfficiency.clear();
    std::stringstream ss(qe);
    std::string cell;
    while (std::getline(ss, cell, ','))
      cam.quantumEfficiency.push_back(nx::parseNumber(cell, "--qe", "a quantum efficiency"));
    // Every output is checked before any is written (the EXR was left behind when --envi
    // was refused after it).
    nx::noteInputFile(input); // no output may replace it (core/input_files.h)
    nx::checkExrOutputName(output);
    nx::checkWritable(output);
    if (!envi.empty()) nx::checkEnviOutputName(envi);
    nx::SpectralImage img = nx::readSpectralExr(input);
    const int nb = img.bands.count();
    nx::validateCameraModel(cam, nb, "nxcamera");
    std::vector<nx::CameraBand> bands;
    for (int b = 0; b < nb; ++b)
      bands.push_back({img.bands.centroid(b), img.bands.responseIntegral(b)});
    const size_t pixels = static_cast<size_t>(img.width) * static_cast<size_t>(img.height);
    std::vector<float> dn;
    try {
      dn = nx::simulateCamera(cam, bands, img.radiance, pixels);
    } catch (const nx::Error& e) {
      throw nx::Error(input + ": " + e.what());
    }
    nx::SpectralImage out;
    out.width = img.width;
    out.height = img.height;
    out.originX = img.originX;
    out.originY = img.originY;
    out.fullWidth = img.fullWidth;
    out.fullHeight = img.fullHeight;
    out.bands = img.bands;
    out.radiance = dn;
    // Each value's variance (the camera's noise and the render's own error), so a comparison
    // with a render has the capture's side of the z-scores.
    out.bandVariance = nx::cameraVariance(cam, bands, img.radiance, img.bandVariance, pixels);
    // The preview: the mean DN over the bands, as grey relative to the largest DN.
    const double maxDn = std::ldexp(1.0, cam.bitDepth) - 1;
    for (size_t p = 0; p < pixels; ++p) {
      double sum = 0;
      for (int b = 0; b < nb; ++b) sum += dn[p * static_cast<size_t>(nb) + static_cast<size_t>(b)];
      const float g = static_cast<float>(sum / nb / maxDn);
      out.rgb.insert(out.rgb.end(), {g, g, g});
    }
    if (img.attributes.count("nxrender.bands"))
      out.attributes["nxrender.bands"] = img.attributes["nxrender.bands"];
    out.attributes["nxcamera.units"] = "DN";
    out.attributes["nxcamera.source"] = input;
    std::ostringstream model;
    model << "f-number " << cam.fNumber << ", transmittance " << cam.lensTransmittance
          << ", irradiance scale " << cam.irradianceScale << ", exposure " << cam.exposureSeconds
          << " s, pitch " << cam.pixelPitchUm << " um, qe " << qe << ", full well "
          << cam.fullWellElectrons << " e, read noise " << cam.readNoiseElectrons
          << " e, dark current " << cam.darkCurrentElectrons << " e/s, gain "
          << cam.gainDnPerElectron << " DN/e, offset " << cam.offsetDn << " DN, " << cam.bitDepth
          << " bits, seed " << cam.seed;
    out.attributes["nxcamera.model"] = model.str();
    nx::writeSpectralExr(output, out);
    if (!envi.empty()) nx::writeEnvi(envi, out);
    double electrons = 0;
    for (int b = 0; b < nb; ++b) {
      double sum = 0;
      for (size_t p = 0; p < pixels; ++p)
        sum += img.radiance[p * static_cast<size_t>(nb) + static_cast<size_t>(b)];
      electrons += nx::meanSignalElectrons(cam, bands[static_cast<size_t>(b)], b,
                                           sum / static_cast<double>(pixels));
    }
    std::printf(
        "nxcamera: %s -> %s%s (%d x %d, %d bands): mean signal %.4g electrons per pixel and band\n",
        input.c_str(), output.c_str(), envi.empty() ? "" : (" and " + envi).c_str(), img.width,
        img.height, nb, electrons / nb);
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "nxcamera: error: %s\n", e.what());
    return 1;
  }
}
