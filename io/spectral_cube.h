#pragma once
// Spectral cubes from the files a lab has: this project's spectral EXR, ENVI cubes and
// multi-band TIFFs (both read with GDAL) and stacks of per-band PNGs, for comparing a render
// with a capture.

#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace nx {

/// A spectral image of any origin: values[pixel][band], row 0 at the top.
struct SpectralCube {
  std::string path;   ///< the file it was read from (for messages)
  std::string format; ///< e.g. "spectral EXR", "ENVI (BIL, int16)"
  int width = 0, height = 0;
  std::vector<double> wavelengthNm; ///< band centres, nm
  std::vector<double> fwhmNm;       ///< band widths, nm; empty when the file gives none
  std::vector<float> values;        ///< [pixel][band]
  std::vector<float> variance;      ///< [pixel][band] variance of each value; empty: unknown
  std::vector<uint32_t> objectId;   ///< [pixel] object id (renders with the ids AOV); or empty
  /// The wavelengths naming the bands (a measured sensor's nominal centres; else wavelengthNm)
  std::vector<double> channelNm;
  std::vector<std::string> bandNames; ///< the bands' own names (this project's EXRs), or empty
  /// This project's EXRs: the sensor's exact description (nxrender.bands); empty otherwise
  std::string sensorText;
  std::map<uint32_t, std::string> objectLabels; ///< object id -> its name (nxrender.objectLabels)
  /// Number of bands.
  int bands() const { return static_cast<int>(wavelengthNm.size()); }
};

/// What a file cannot say about itself, given on the command line.
struct CubeReadOptions {
  std::vector<double> wavelengthNm; ///< band centres when the file has none (or to override)
  std::vector<double> fwhmNm;       ///< band widths likewise (one value for all, or one per band)
};

/// Reads a spectral EXR (by its .exr extension), an ENVI cube (named by its .hdr header or by
/// its data file; BSQ, BIL or BIP; byte, int16, uint16, int32, uint32, float32, float64; either
/// byte order; `wavelength` and `fwhm` from the header, in nm or micrometres) or a multi-band
/// TIFF (wavelengths from the bands' `wavelength` metadata or from `options`), or a directory
/// of per-band 8- or 16-bit grey PNGs in natural name order (the CAVE layout; raw values,
/// wavelengths from `options`). Throws
/// nx::Error naming the file and what is wrong: no wavelength list, a data file shorter than
/// its header says, a header without a data file, an unknown format.
SpectralCube readSpectralCube(const std::string& path, const CubeReadOptions& options = {});

/// Parses an ENVI list "{a, b, c}" (braces optional) of numbers; `what` names it in errors.
std::vector<double> parseEnviNumberList(const std::string& text, const std::string& where,
                                        const std::string& what);

} // namespace nx
