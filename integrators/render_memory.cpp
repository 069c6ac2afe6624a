#include "integrators/render_memory.h"

#include <string>

#include "core/memory.h"
#include "io/exr_write_cost.h"

namespace nx {

double renderExtraBytes(const RenderExtras& e, const std::optional<RenderFileOutput>& output) {
  const double pixels = static_cast<double>(e.width) * e.height;
  const double layerValues = pixels * e.layers * e.bands;
  const double relightValues =
      pixels * static_cast<double>(e.relightEntries) * static_cast<double>(e.relightSources);
  // Film: layer sums in doubles, transport sums in floats, each twice (the two replicates).
  double bytes = layerValues * 16 + relightValues * 8;
  // The image: means and variances (half-differences) in floats.
  bytes += layerValues * 8 + relightValues * 8;
  // Each running task's pixel accumulator (both replicates, doubles).
  bytes += static_cast<double>(e.threads) * 16.0 *
           (static_cast<double>(e.layers) * e.bands +
            static_cast<double>(e.relightEntries * e.relightSources));
  if (output) {
    ExrImageShape shape;
    shape.width = e.width, shape.height = e.height, shape.bands = e.bands;
    shape.white = e.whiteReference, shape.ids = e.ids, shape.depth = e.depth;
    shape.bandVariance = shape.yVariance = shape.layerVariances = !output->withoutVariance;
    shape.layers = e.layers;
    shape.relightSources = e.relightSources;
    shape.relightPlanes = e.relightEntries * e.relightSources;
    shape.relightBins = e.relightBins;
    bytes += exrWriteBytes(shape, output->encoding, output->halfFloats);
    if (output->withoutVariance) bytes += layerValues * 4 + relightValues * 8; // the copy
  }
  return bytes;
}

void requireRenderExtrasMemory(const RenderExtras& e,
                               const std::optional<RenderFileOutput>& output) {
  if (e.layers == 0 && e.relightSources == 0) return;
  std::string what, found;
  if (e.layers > 0) {
    what = "component layers";
    found = std::to_string(e.layers) + " layers" +
            (e.lightGroupLayers > 0 ? " (" + std::to_string(e.lightGroupLayers) + " light groups)"
                                    : std::string()) +
            " x " + std::to_string(e.bands) + " bands";
  }
  if (e.relightSources > 0) {
    what += std::string(what.empty() ? "" : ", ") + "a transport";
    found += std::string(found.empty() ? "" : ", ") + std::to_string(e.relightEntries) +
             " entries per light source x " + std::to_string(e.relightSources) + " sources";
  }
  what += output ? " and the EXR holding them" : "";
  found += " x " + std::to_string(e.width) + "x" + std::to_string(e.height) + " pixels";
  if (e.relightSources > 0)
    found += " (a coarser --relight-step, fewer bands or a --crop per part need less)";
  else
    found += " (fewer light groups, or a --crop per part, need less)";
  const std::string where = e.relightSources > 0     ? "--relightable"
                            : e.lightGroupLayers > 0 ? "--aov lightgroups"
                                                     : "--aov components";
  requireMemory(renderExtraBytes(e, output), where, what, found);
}

} // namespace nx
