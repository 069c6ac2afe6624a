// libFuzzer target for the lab's input files, one kind per run (NX_FUZZ_KIND): ply and obj
// (structural check, the mesh library, the mesh's own validation), sensor (a measured
// response CSV, its response table and wavelength sampler), envi (a header beside a small
// data file, read as a cube) and exr (read as a spectral image). nx::Error is the expected
// reaction to bad input; anything else (a crash, a sanitizer report, another exception, a
// hang, 2 GB of memory) is a finding.

#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>

#include "core/error.h"
#include "io/exr_header_check.h"
#include "io/mesh_reader.h"
#include "io/spectral_cube.h"
#include "io/spectral_exr.h"
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
  const char* kind = std::getenv("NX_FUZZ_KIND");
  gKind = kind ? kind : "";
  if (gKind != "ply" && gKind != "obj" && gKind != "sensor" && gKind != "envi" && gKind != "exr") {
    std::fprintf(stderr, "input_fuzzer: set NX_FUZZ_KIND to ply, obj, sensor, envi or exr\n");
    std::exit(2);
  }
  if (gKind == "envi" || gKind == "exr") { // these are read from files: a directory of its own
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
      nx::readSpectralExr(gDir + "/image.exr");
    }
  } catch (const nx::Error&) {
  }
  return 0;
}
