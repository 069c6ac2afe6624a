#pragma once
// Spectral OpenEXR files in the layout of Fichet, Pacanowski & Wilkie, "An OpenEXR Layout
// for Spectral Images", JCGT 10(3), 2021.

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "io/exr_compression.h"

#include "io/relight_layers.h"
#include "spectra/cie.h"
#include "spectra/sensor.h"

namespace nx {

/// A component layer of a spectral image (--aov components, lightgroups): per band, the part of
/// the radiance carried by one class of paths, and the variance of its mean.
struct ImageLayer {
  std::string name;             ///< "reflected", "fluoresced", "direct", "indirect", "light.NAME"
  std::vector<float> values;    ///< [pixel][band], like SpectralImage::radiance
  std::vector<float> variances; ///< [pixel][band]; empty: not stored
};

/// A ground-truth layer (--aov normals, position, uv, albedo, ...; io/aov_names.h): per pixel
/// the mean of its channels over the pixel's samples, like the radiance.
struct AovImageLayer {
  std::string name;          ///< "normals", "albedo", ... (aovName)
  std::vector<float> values; ///< [pixel][channel], channels as aovChannelNames lists them
};

/// A spectral image, or a rectangular part (crop) of one: band radiances, a linear sRGB
/// preview and per-pixel sample counts.
struct SpectralImage {
  int width = 0, height = 0;         ///< size of the stored region (EXR data window)
  int originX = 0, originY = 0;      ///< its top-left pixel in the full image
  int fullWidth = 0, fullHeight = 0; ///< the full image (EXR display window); 0 = the region
  Sensor bands;
  std::vector<float> radiance;     ///< [pixel][band], W m^-2 sr^-1 nm^-1 averaged over the band
  std::vector<float> rgb;          ///< [pixel][3], linear sRGB (D65), negatives already clamped
  std::vector<float> xyz;          ///< [pixel][3], CIE XYZ (unclamped); empty: not stored
  std::vector<float> bandVariance; ///< [pixel][band] variance of each band mean; empty: not stored
  std::vector<float> yVariance;    ///< [pixel] variance of the mean luminance Y; empty: not stored
  std::vector<uint32_t> sampleCount; ///< [pixel] samples behind each value; empty: not stored
  /// [pixel][band] the radiance a white Lambertian surface (reflectance 1) would reflect at
  /// the first hit (a white reference for flat-fielding); empty: not stored
  std::vector<float> white;
  std::vector<uint32_t> objectId;   ///< [pixel] object seen at the pixel centre (0: none)
  std::vector<uint32_t> materialId; ///< [pixel] its material (0: none)
  std::vector<float> depth; ///< [pixel] camera-space z of the surface at the pixel centre (0: none)
  /// Component layers, as EXR channels <name>.S0.<band>nm and Variance.<name>.S0.<band>nm,
  /// listed in the attribute nxrender.componentLayers
  std::vector<ImageLayer> layers;
  /// Ground-truth layers, as EXR channels <name>.<channel> (normals.X, albedo.T.550,000000nm),
  /// listed in the attribute nxrender.aovLayers
  std::vector<AovImageLayer> aovs;
  /// The transport of a relightable render (--relightable), as EXR channels
  /// relight.<group>.T.<excitation>nm.<band>nm (and .X, .Y, .Z) with HalfDifference.<...>
  RelightLayers relight;
  std::map<std::string, std::string> attributes; ///< provenance, written as string attributes
  /// The files it was read from (kept by what is made of it: a relit image, a merge); never
  /// written, and no writer replaces one of them with it (it would destroy its own source).
  std::vector<std::string> sourceFiles;

  /// Full image size (the region's when fullWidth/fullHeight are 0).
  int displayWidth() const { return fullWidth > 0 ? fullWidth : width; }
  int displayHeight() const { return fullHeight > 0 ? fullHeight : height; }
};

/// Throws nx::Error if writing `image` to `path` would replace a file the image was read from
/// (through a link, a hard link or another spelling) or an input of the program.
void refuseOverwritingASource(const std::string& path, const SpectralImage& image);

/// Sets pixel i's X, Y, Z to `xyz` and its R, G, B to linear sRGB from it, negatives clamped to
/// 0 (the buffers sized by the caller).
void setPixelColour(SpectralImage& image, size_t i, const Xyz& xyz);

/// Name of the per-pixel sample-count channel (not a spectral channel name).
inline constexpr const char* kSampleCountChannel = "SampleCount";
/// Prefix of the variance channels ("Variance.Y", "Variance.S0.550,000000nm").
inline constexpr const char* kVariancePrefix = "Variance.";
/// Prefix of the white-reference channels ("white.S0.550,000000nm").
inline constexpr const char* kWhitePrefix = "white.";
/// The attribute listing an image's ground-truth layers (comma-separated).
inline constexpr const char* kAovLayersAttribute = "nxrender.aovLayers";
/// The attribute listing an image's component layers (comma-separated, in channel order).
inline constexpr const char* kComponentLayersAttribute = "nxrender.componentLayers";
/// Names of the id and depth channels.
inline constexpr const char* kObjectIdChannel = "ObjectId";
inline constexpr const char* kMaterialIdChannel = "MaterialId";
inline constexpr const char* kDepthChannel = "Depth";

/// The attributes naming each band of `bands` (written with every spectral EXR, derived
/// again when read): nxrender.bandNames, nxrender.bandCentroids, nxrender.bandFwhm.
std::map<std::string, std::string> bandAttributes(const Sensor& bands);

/// Channel name of a band centred at nm for Stokes component 0, e.g. "S0.550,000000nm"
/// (a comma as decimal separator, since a dot separates EXR layers).
std::string spectralChannelName(double nm);

/// Throws nx::Error unless `path` ends in .exr (any case): an EXR is never written under another
/// format's name (x.png holding EXR data).
void checkExrOutputName(const std::string& path);

/// Writes the image as an OpenEXR with float channels S0.<band>nm, R, G, B and (when present)
/// X, Y, Z, Variance.Y and Variance.S0.<band>nm (error estimates of the means), a uint channel
/// SampleCount (none of these names is a spectral one), the data
/// window of the region inside the display window of the full image, the attributes
/// spectralLayoutVersion = "1.0" and emissiveUnits = "W.m^-2.sr^-1", and every provenance
/// attribute. The file appears atomically (temporary name, then rename). `encoding`: the
/// compression (default: none for floats, piz for half floats; see defaultExrCompression).
/// Refused, writing nothing: a name not ending in .exr, a NaN or infinite value (named with its
/// channel and pixel).
void writeSpectralExr(const std::string& path, const SpectralImage& image,
                      const ExrEncoding& encoding = {});

/// The same with every float channel stored as a half float (16 bits: about 3 significant
/// digits, values up to 65504; SampleCount stays a 32-bit integer), half the size. Throws
/// nx::Error, writing nothing, when a value would not fit (see fitsInHalf).
void writeSpectralExrHalf(const std::string& path, const SpectralImage& image,
                          const ExrEncoding& encoding = {});

/// True when every value of the image's float channels is finite and at most 65504 in size
/// (the largest half float), so writeSpectralExrHalf keeps it.
bool fitsInHalf(const SpectralImage& image);

/// Largest EXR file read (bytes); only regular files are opened (a FIFO is refused unread).
inline constexpr std::uintmax_t kMaxExrFileBytes = 1ull << 40;

/// Reads a spectral EXR: one written by writeSpectralExr (bands from the nxrender.bands
/// attribute), or any file of the Fichet et al. layout (bands from the channel names: S0, else
/// T channels, in any SI unit of length or frequency; evenly spaced wavelengths become uniform
/// boxes, others Gaussians as wide as the spacing; a missing RGB is computed from the bands,
/// the attribute nxrender.spectralChannels says S0 or T). Errors name the file and what is
/// wrong; a file whose pixels would not fit in memory is refused with figures before
/// any is read.
SpectralImage readSpectralExr(const std::string& path);

/// The size of an EXR's contents from its header alone (memory checks before reading).
struct ExrFootprint {
  double dataPixels = 0;    ///< pixels of the data window (stored)
  double displayPixels = 0; ///< pixels of the display window (the full image)
  double channels = 0;      ///< channels per pixel (each read as 4 bytes)
};

/// The footprint of the EXR at `path` (reads the header only).
ExrFootprint spectralExrFootprint(const std::string& path);

} // namespace nx
