#pragma once
// Merging the transport of relightable parts (crops and sample ranges, docs/farm.md).

#include <cstdint>
#include <vector>

#include "io/part_merge.h"

namespace nx {

/// The transport of the merged image (width x height, the parts placed by their origins): per
/// pixel the parts' means weighted by their sample counts (`count`: the merged counts), and
/// their signed half-differences likewise, so that (c . d)^2 stays an unbiased estimate of the
/// merged relit error (the parts are independent). A pixel of one part keeps its values bit
/// for bit. Empty when no part holds a transport; throws, naming the part, when some parts
/// hold one and others not, or they differ in groups, grid, pattern or spectra.
RelightLayers mergeRelight(const std::vector<ImagePart>& parts, int width, int height,
                           const std::vector<uint64_t>& count);

} // namespace nx
