#pragma once
// Merging the parts of a render (crops, sample ranges, band ranges) into one image.

#include <string>
#include <utility>
#include <vector>

#include "io/spectral_exr.h"

namespace nx {

/// A part to merge: its file name (for messages) and its content.
struct ImagePart {
  std::string name;
  SpectralImage image;
};

/// Assembles crops and averages sample ranges weighted by their per-pixel sample counts.
/// A pixel covered by one part keeps that part's values bit for bit; pixels covered by
/// several get sum(mean * count) / sum(count), computed in double from the parts' float
/// means (so a split by sample ranges equals one render of their union up to the float
/// rounding of the parts' means). Refuses, naming the offending part: parts of different
/// scenes or render options, seeds, bands or resolutions; parts holding fewer samples than
/// their range says (interrupted); overlapping sample ranges on the same pixels (overlapping
/// crops or repeated ranges); and reports missing regions (pixels with fewer samples than
/// the best-covered pixel).
/// Parts with different bands (renders of disjoint band ranges, e.g. one per farm node) are
/// merged per band set, then stitched into one image holding every band, ordered by centroid:
/// they must share the scene, options, seed, pixels and sample counts, no band may appear in
/// two sets, and the sets must be of one kind (boxes, Gaussians or measured responses). XYZ,
/// RGB and Variance.Y are the first set's.
SpectralImage mergeParts(const std::vector<ImagePart>& parts);

} // namespace nx
