#include "io/preview_image.h"

#include <algorithm>
#include <cctype>

#define STB_IMAGE_WRITE_IMPLEMENTATION
#define STBI_WRITE_NO_STDIO_FILENAME_CONVERSION
#include <stb/stb_image_write.h>

#include "core/error.h"
#include "io/atomic_file.h"

namespace nx {
namespace {
std::string lowerExtension(const std::string& path) {
  const auto dot = path.find_last_of('.');
  if (dot == std::string::npos || path.find('/', dot) != std::string::npos) return {};
  std::string ext = path.substr(dot);
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return std::tolower(c); });
  return ext;
}
} // namespace

bool isPreviewPath(const std::string& path) {
  const std::string ext = lowerExtension(path);
  return ext == ".png" || ext == ".bmp";
}

void writePreview(const std::string& path, int width, int height, const std::vector<uint8_t>& rgb) {
  const std::string ext = lowerExtension(path);
  if (ext != ".png" && ext != ".bmp")
    throw Error(path + ": expected a preview file name ending in .png or .bmp, found '" + ext +
                "'");
  if (width <= 0 || height <= 0 ||
      rgb.size() != static_cast<size_t>(width) * static_cast<size_t>(height) * 3)
    throw Error(path + ": internal error: preview buffer does not match its size");
  writeAtomically(path, [&](const std::string& temp) {
    const int ok = ext == ".png"
                       ? stbi_write_png(temp.c_str(), width, height, 3, rgb.data(), width * 3)
                       : stbi_write_bmp(temp.c_str(), width, height, 3, rgb.data());
    if (!ok) throw Error("the image encoder failed (disk full or unwritable?)");
  });
}

} // namespace nx
