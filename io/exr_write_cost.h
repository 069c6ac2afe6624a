#pragma once
// What writing a spectral EXR costs in memory, known before the image exists: its channels
// (from the image's shape) and the buffers OpenEXR allocates to write them, so that a render
// whose file could not be written is refused before it starts (a finished relightable render
// was lost at the write).

#include <cstddef>

#include "io/exr_compression.h"

namespace nx {

struct SpectralImage;

/// What a spectral image holds, as far as its file's channels go.
struct ExrImageShape {
  int width = 0, height = 0, bands = 0;
  bool xyz = true, bandVariance = true, yVariance = true, sampleCount = true;
  bool white = false, ids = false, depth = false;
  int layers = 0;             ///< component layers (each a channel per band)
  bool layerVariances = true; ///< and each a variance channel per band
  size_t relightPlanes = 0;   ///< transport entries over all its sources (two channels each)
  size_t relightBins = 0;     ///< the transport's excitation bins (its spectra's attributes)
  size_t relightSources = 0;
};

/// The shape of an image.
ExrImageShape shapeOf(const SpectralImage& image);

/// The channels writeSpectralExr writes for an image of this shape.
size_t exrChannelCount(const ExrImageShape& shape);

/// The threads OpenEXR writes with (each keeps two line buffers): the render's, or none when
/// one buffer of a chunk of `chunkBytes` would pass 64 MiB (a relightable file's lines hold
/// millions of channels).
int exrWriterThreads(double chunkBytes);

/// Bytes the writer allocates beyond the image for a file of this shape: OpenEXR's line
/// buffers (max(1, 2 threads), a chunk of lines each) and their compressors' buffers, its
/// channel tables (the header's twice, the frame buffer's: 256-byte names), half-float copies.
double exrWriteBytes(const ExrImageShape& shape, const ExrEncoding& encoding, bool halfFloats);

} // namespace nx
