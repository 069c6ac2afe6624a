#pragma once
// What a render allocates beyond its film's bands, counted before it is allocated: component
// layers (one per light group with --aov lightgroups), the transport of a relightable render,
// their image and the EXR writer's buffers. 1000 light groups at 320x240 grew to 23 GiB and
// were killed; a relightable render of 1000 groups passed its check and was lost at the write.

#include <cstddef>
#include <optional>

#include "integrators/renderer.h"

namespace nx {

/// The parts of a render that scale with its layers and transport.
struct RenderExtras {
  int width = 0, height = 0, bands = 0;
  int layers = 0;            ///< component layers
  int lightGroupLayers = 0;  ///< of which one per light group
  size_t relightEntries = 0; ///< transport entries per source
  size_t relightSources = 0; ///< light sources with a transport
  size_t relightBins = 0;    ///< excitation bins of the transport's spectra
  bool whiteReference = false;
  bool ids = false, depth = false;
  int threads = 1; ///< tile tasks running at once (each holds a pixel accumulator)
};

/// Bytes allocated for `extras`: the film's sums (two doubles per layer value, two floats per
/// transport value), the image's means and variances (two floats each), each running task's
/// pixel accumulator, and, when the image is written (`output`), the EXR writer's buffers
/// (exrWriteBytes) and a copy without variances where that is asked.
double renderExtraBytes(const RenderExtras& extras, const std::optional<RenderFileOutput>& output);

/// Throws nx::Error "--aov lightgroups: expected component layers, a transport and their EXR
/// whose buffers fit in memory, found ... (needs X GiB; Y GiB usable: ...)" when they do not.
void requireRenderExtrasMemory(const RenderExtras& extras,
                               const std::optional<RenderFileOutput>& output);

} // namespace nx
