#pragma once
// Export of a spectral image as an ENVI cube (the format of hyperspectral cameras and their
// tools): BSQ float32 data with a .hdr header listing each band's wavelength and FWHM.

#include <string>

#include "io/spectral_exr.h"

namespace nx {

/// Writes the image's spectral bands to `dataPath` (BSQ, float32, little-endian) and the ENVI
/// header beside it (dataPath with its extension replaced by .hdr): samples, lines, bands,
/// wavelength units = Nanometers, wavelength (the bands' centroids), fwhm, band names, and
/// the sensor description. Written through GDAL's ENVI driver; both files replace existing
/// ones only once complete. Throws nx::Error naming the path on failure.
void writeEnvi(const std::string& dataPath, const SpectralImage& image);

/// Throws nx::Error unless `dataPath` can be written as an ENVI cube: its name is not the
/// header's (an extension other than .hdr), and both files can be written (checkWritable).
void checkEnviOutputName(const std::string& dataPath);

/// The header path GDAL gives the data file `dataPath` (its extension replaced by .hdr).
std::string enviHeaderPath(const std::string& dataPath);

} // namespace nx
