// nxmerge: assembles the parts of a render (crops, sample ranges, any mix) into one image.
//
//   nxmerge -o OUT.exr PART.exr [PART.exr ...]
//
// Writes OUT.exr and its preview OUT.png. Refuses parts that do not belong together, naming
// the part, and reports missing regions; then nothing is written and the exit status is 1.

#include <CLI/CLI.hpp>

#include <cstdio>
#include <filesystem>

#include "apps/command_line.h"
#include "core/error.h"
#include "core/input_files.h"
#include "core/memory.h"
#include "integrators/renderer.h"
#include "io/atomic_file.h"
#include "io/envi_export.h"
#include "io/part_merge.h"
#include "io/preview_image.h"
#include "io/spectral_exr.h"
#include "spectra/colour.h"

int main(int argc, char** argv) {
  CLI::App app{"nxmerge: merges crops, sample ranges and band ranges of an nxrender image"};
  std::string output;
  std::vector<std::string> inputs;
  bool envi = false;
  app.add_flag("--envi", envi,
               "Also write the merged bands as an ENVI cube beside it (OUT.img and OUT.hdr)");
  app.add_option("-o,--output", output, "Merged spectral EXR (its preview goes beside it as .png)")
      ->required();
  app.add_option("parts", inputs,
                 "Parts written by nxrender (--crop, --spp-range, --tile-of-array, or disjoint "
                 "--bands/--sensor ranges of the same scene, seed and samples)")
      ->required();
  if (const int status = nx::parseCommandLine(app, argc, argv, "nxmerge"); status >= 0)
    return status;
  try {
    for (const auto& path : inputs) nx::noteInputFile(path); // no output may replace one
    nx::checkExrOutputName(output);
    const std::string preview = std::filesystem::path(output).replace_extension(".png").string();
    nx::checkWritable(output);
    nx::checkWritable(preview);
    const std::string enviPath =
        envi ? std::filesystem::path(output).replace_extension(".img").string() : std::string();
    if (envi) nx::checkEnviOutputName(enviPath);
    // Every part is held in memory with the merged image (floats) and its double-precision
    // sums: checked from the headers before anything is read (two 1080p parts took 2.7 GiB).
    double bytes = 0;
    for (const auto& path : inputs) {
      const nx::ExrFootprint f = nx::spectralExrFootprint(path);
      bytes += f.dataPixels * f.channels * 4.0;
      if (&path == &inputs.front()) bytes += f.displayPixels * f.channels * (4.0 + 8.0);
    }
    nx::requireMemory(bytes, output, "parts", std::to_string(inputs.size()) + " parts");
    std::vector<nx::ImagePart> parts;
    for (const auto& path : inputs) parts.push_back({path, nx::readSpectralExr(path)});
    const nx::SpectralImage merged = nx::mergeParts(parts);
    {
      const nx::OutputLock lock(output); // the EXR and its preview as one pair
      nx::AtomicFileGroup pair;          // replaced together (see AtomicFileGroup)
      nx::writeSpectralExr(output, merged);
      nx::writePreview(preview, merged.width, merged.height, nx::previewPixels(merged));
      pair.commit();
      if (envi) nx::writeEnvi(enviPath, merged);
    }
    std::fprintf(stderr, "nxmerge: merged %zu parts into %s and %s (%dx%d, samples %s)\n",
                 parts.size(), output.c_str(), preview.c_str(), merged.width, merged.height,
                 merged.attributes.at("nxrender.sampleRange").c_str());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "nxmerge: error: %s\n", e.what());
    return 1;
  }
  return 0;
}
