#pragma once
// 8-bit preview images: PNG and BMP.

#include <cstdint>
#include <string>
#include <vector>

namespace nx {

/// Writes interleaved 8-bit RGB pixels (top row first) as PNG or BMP, chosen by the
/// extension of `path` (.png or .bmp, any case); BMP rows are padded to 4 bytes. The file
/// appears atomically. Unknown extensions are an nx::Error.
void writePreview(const std::string& path, int width, int height, const std::vector<uint8_t>& rgb);

/// True when `path` ends in an extension writePreview understands.
bool isPreviewPath(const std::string& path);

} // namespace nx
