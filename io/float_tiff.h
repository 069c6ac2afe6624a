#pragma once
// Single-band float32 GeoTIFF images (maps such as nxcompare's spectral angles), for tools
// like Python with GDAL or OpenImageIO.

#include <string>
#include <vector>

namespace nx {

/// Writes width x height float values (row 0 at the top) as a one-band float32 TIFF through
/// GDAL, NaN marked as no-data, `description` as the band's description; the file appears
/// atomically. Throws nx::Error naming the path on failure.
void writeFloatTiff(const std::string& path, int width, int height,
                    const std::vector<float>& values, const std::string& description);

} // namespace nx
