// libFuzzer target: the scene loader and build step, the numeric-table and matrix CSV
// readers, and the band parser, on arbitrary bytes. nx::Error is the expected reaction to bad
// input; anything else (a crash, a sanitizer report, another exception, a hang) is a finding.

#include <cstddef>
#include <cstdint>
#include <string>

#include "core/error.h"
#include "core/text_table.h"
#include "integrators/render_scene.h"
#include "integrators/scene_reader.h"
#include "spectra/bands.h"
#include "spectra/reradiation_matrix.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    nx::resolveRenderScene(nx::parseScene(text, "fuzz.scn"));
  } catch (const nx::Error&) {
  }
  try {
    nx::parseNumberTable(text, "fuzz.csv", true);
  } catch (const nx::Error&) {
  }
  try {
    nx::ReradiationMatrix::fromMeasured(nx::parseMeasuredMatrixCsv(text, "fuzz.csv"));
  } catch (const nx::Error&) {
  }
  if (size < 64) {
    try {
      nx::SpectralBands::parse(text);
    } catch (const nx::Error&) {
    }
  }
  return 0;
}
