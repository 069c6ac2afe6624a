#pragma once
// How a spectral EXR's pixels are compressed: OpenEXR's methods by name, which of them keep
// every bit, and the zlib level of the zip methods.

#include <optional>
#include <string>
#include <vector>

namespace nx {

/// OpenEXR's compression methods (the file format's own list, in its order).
enum class ExrCompression { None, Rle, Zips, Zip, Piz, Pxr24, B44, B44a, Dwaa, Dwab };

/// How writeSpectralExr encodes the pixels.
struct ExrEncoding {
  /// The compression method; unset: defaultExrCompression of the stored type.
  std::optional<ExrCompression> compression;
  /// zlib level 1-9 for zip and zips; ignored by the other methods.
  int zipLevel = 4;
};

/// The compression chosen by measurement (docs/performance.md, nxbench-exr): none for float
/// channels (a render's noisy mantissas do not compress: zip saves 2-3% and takes 40 times
/// longer than writing), piz for half floats (it halves the file again, fastest of the
/// lossless methods).
ExrCompression defaultExrCompression(bool halfFloats);

/// The method's name as the command line spells it: none, rle, zips, zip, piz, pxr24, b44,
/// b44a, dwaa, dwab.
const char* exrCompressionName(ExrCompression c);
/// Every method, in the file format's order.
std::vector<ExrCompression> allExrCompressions();
/// True when the method stores float channels bit for bit (none, rle, zips, zip, piz; B44
/// keeps floats too but compresses only half channels).
bool keepsFloatsExactly(ExrCompression c);
/// Scan lines per chunk of the method (1 for none, rle, zips; 16 for zip; 32 for piz; ...).
int exrChunkLines(ExrCompression c);
/// The buffers OpenEXR's compressor for the method allocates, in multiples of a chunk's raw
/// bytes (0 for none).
double exrCompressorBuffers(ExrCompression c);
/// The method named `text` (see exrCompressionName); throws nx::Error naming `what` and the
/// accepted names otherwise.
ExrCompression parseExrCompression(const std::string& text, const std::string& what);

} // namespace nx
