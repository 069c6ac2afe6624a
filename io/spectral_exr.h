#pragma once
// Spectral OpenEXR files in the layout of Fichet, Pacanowski & Wilkie, "An OpenEXR Layout
// for Spectral Images", JCGT 10(3), 2021.

#include <map>
#include <string>
#include <vector>

#include "spectra/bands.h"

namespace nx {

/// A spectral image ready to be written: band radiances plus a linear sRGB preview.
struct SpectralImage {
  int width = 0, height = 0;
  SpectralBands bands;
  std::vector<float> radiance; ///< [pixel][band], W m^-2 sr^-1 nm^-1 averaged over the band
  std::vector<float> rgb;      ///< [pixel][3], linear sRGB (D65), negatives already clamped
  std::map<std::string, std::string> attributes; ///< provenance, written as string attributes
};

/// Channel name of a band centred at nm for Stokes component 0, e.g. "S0.550,000000nm"
/// (a comma as decimal separator, since a dot separates EXR layers).
std::string spectralChannelName(double nm);

/// Writes the image as a float32 OpenEXR with channels S0.<band>nm and R, G, B, the
/// attributes spectralLayoutVersion = "1.0" and emissiveUnits = "W.m^-2.sr^-1", and every
/// provenance attribute. The file appears atomically (temporary name, then rename).
void writeSpectralExr(const std::string& path, const SpectralImage& image);

} // namespace nx
