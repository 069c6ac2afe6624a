// libFuzzer target for the lab's input files, one kind per run (NX_FUZZ_KIND): ply and obj
// (structural check, the mesh library, the mesh's own validation), sensor (a measured
// response CSV, its response table and wavelength sampler), envi (a header beside a small
// data file, read as a cube), exr (read as a spectral image), eem (an instrument EEM CSV
// through its whole import: scatter removal, the absolute matrix, the 5 nm grid; the first
// byte picks the layout), calibration (an OpenCV FileStorage YAML or XML file read for a view
// the first byte picks), concentration (a concentration-map CSV) and relight (a relightable
// EXR read, checked and relit to its own spectra). nx::Error is the expected reaction to bad
// input; anything else (a crash, a sanitizer report, another exception, a hang, 2 GB of
// memory) is a finding.

#include <unistd.h>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>

#include "core/error.h"
#include "core/params/concentration_map.h"
#include "integrators/relight_image.h"
#include "io/exr_header_check.h"
#include "io/mesh_reader.h"
#include "io/opencv_calibration.h"
#include "io/spectral_cube.h"
#include "io/spectral_exr.h"
#include "spectra/eem_import.h"
#include "spectra/sensor.h"
#include "spectra/wavelength_sampler.h"

namespace {

std::string gKind, gDir;

void writeFile(const std::string& path, const uint8_t* data, size_t size) {
  std::ofstream(path, std::ios::binary)
      .write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
}

} // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  // A crash of OpenCV's reader inside its helper process (a program of its own, not a fork of
  // this one) is contained and refused as a file error: only this process's crashes are findings.
  const char* kind = std::getenv("NX_FUZZ_KIND");
  gKind = kind ? kind : "";
  static const char* kKinds[] = {"ply", "obj",         "sensor",        "envi",   "exr",
                                 "eem", "calibration", "concentration", "relight"};
  if (std::find(std::begin(kKinds), std::end(kKinds), gKind) == std::end(kKinds)) {
    std::fprintf(stderr, "input_fuzzer: set NX_FUZZ_KIND to ply, obj, sensor, envi, exr, eem, "
                         "calibration, concentration or relight\n");
    std::exit(2);
  }
  if (gKind == "envi" || gKind == "exr" || gKind == "relight") { // read from files: a directory
    gDir =
        (std::filesystem::temp_directory_path() / ("nx-input-fuzz-" + std::to_string(::getpid())))
            .string();
    std::filesystem::create_directories(gDir);
    std::atexit([] {
      std::error_code ec;
      std::filesystem::remove_all(gDir, ec);
    });
  }
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string bytes(reinterpret_cast<const char*>(data), size);
  try {
    if (gKind == "ply" || gKind == "obj") {
      nx::meshFromBytes(bytes, "fuzz." + gKind);
    } else if (gKind == "sensor") {
      const nx::Sensor sensor = nx::Sensor::fromCsv(bytes, "fuzz.csv");
      const nx::SensorResponseTable table(sensor);
      (void)nx::WavelengthSampler::forSensor(sensor, nx::kTraceMinNm, nx::kTraceMaxNm);
      (void)nx::Sensor::parse(sensor.toString(), "round trip");
    } else if (gKind == "envi") {
      // The header as fuzzed; the data: 4 x 3 x 2 float32 zeros (what a valid header of that
      // size reads), so that GDAL reaches the data only through our checks.
      writeFile(gDir + "/cube.hdr", data, size);
      static const uint8_t zeros[96] = {};
      writeFile(gDir + "/cube.img", zeros, sizeof zeros);
      nx::readSpectralCube(gDir + "/cube.hdr");
    } else if (gKind == "eem") {
      // The first byte: the layout (rows, units, scatter, one shape) and how it is made absolute.
      const uint8_t flags = size > 0 ? data[0] : 0;
      const std::string text = size > 0 ? bytes.substr(1) : std::string();
      nx::EemLayout layout;
      layout.emissionRows = flags & 1;
      layout.energyUnits = flags & 2;
      layout.rayleighWidthNm = flags & 4 ? 12 : 0;
      layout.ramanShiftCm = flags & 8 ? nx::kWaterRamanShiftCm : 0;
      layout.ramanWidthNm = flags & 8 ? 10 : 0;
      layout.meanEmissionShape = flags & 16;
      nx::EemSummary summary;
      const nx::EemTable clean =
          nx::withoutScatter(nx::parseEemCsv(text, "fuzz.csv", layout), layout, summary);
      nx::EemYield yield;
      if (flags & 32) { // the table as its own reference dye
        yield.reference = &clean;
        yield.referenceYield = 0.9;
        yield.referenceAbsorptance = 0.5;
      } else {
        yield.quantumYield = 0.6;
      }
      nx::EemAbsorptance absorptance;
      if (flags & 64)
        absorptance.spectrum = [](double nm) { return nm < 500 ? 0.8 : 0.1; };
      else
        absorptance.peak = 0.9;
      const nx::MeasuredMatrix m = nx::donaldsonFromEem(clean, layout, yield, absorptance, summary);
      const nx::Spectrum rho(nx::ConstantSpectrum{0.05});
      (void)nx::ReradiationMatrix::fromMeasured(m, &rho);
      (void)summary.text();
    } else if (gKind == "calibration") {
      const uint8_t view = size > 0 ? data[0] : 0;
      const std::string text = size > 0 ? bytes.substr(1) : std::string();
      const std::optional<int> v = view < 128 ? std::optional<int>(view % 4) : std::nullopt;
      // The way a scene reads it (OpenCV in a child process with a time limit) must answer;
      // then, for coverage (a child's is not seen here), the same read in this process unless
      // the child found OpenCV crashing or looping on it.
      bool safe = true;
      try {
        // (an input of 8 kB reads in milliseconds, even under the sanitizers: a loop is known
        // in a quarter of a second)
        (void)nx::parseOpenCvCalibration(text, "fuzz.yml", v, 0.25);
      } catch (const nx::Error& e) {
        const std::string m = e.what();
        safe = m.find("OpenCV's calibration reader: ") == std::string::npos &&
               m.find("NUL byte") == std::string::npos;
      }
      if (safe) (void)nx::readOpenCvCalibrationHere(text, "fuzz.yml", v);
    } else if (gKind == "concentration") {
      const nx::ConcentrationMap m = nx::parseConcentrationCsv(bytes, "fuzz.csv");
      (void)m.at(0.3f, 0.7f);
    } else {
      writeFile(gDir + "/image.exr", data, size);
      // A small file may declare a huge image: it is read (and fails) within the memory
      // budget, which the tests check (SpectralExr.HugeDeclaredImageIsRefusedBeforeAllocating);
      // here such inputs would only measure the allocator, so images over 8 MB are skipped.
      const nx::ExrHeaderSummary h = nx::checkExrHeader(gDir + "/image.exr");
      if (static_cast<double>(h.dataWidth) * static_cast<double>(h.dataHeight) * (h.channels + 3) *
                  4 +
              2 * h.lineBytes * h.chunkLines >
          8e6)
        return 0;
      (void)nx::spectralExrFootprint(gDir + "/image.exr");
      const nx::SpectralImage image = nx::readSpectralExr(gDir + "/image.exr");
      if (gKind == "relight" && image.relight.present()) (void)nx::relightImage(image, {});
    }
  } catch (const nx::Error&) {
  }
  return 0;
}
