#pragma once
// Images decoded with stb_image: colour images (PNG, JPEG) to linear sRGB for reflectance
// textures, and grey images to their raw values for per-band capture stacks.

#include <string>
#include <vector>

namespace nx {

/// A colour image decoded to linear sRGB: rgb[(row * width + column) * 3 + channel], row 0 at
/// the top, each value in [0, 1].
struct LinearSrgbImage {
  int width = 0, height = 0;
  int bitsPerChannel = 8; ///< 8 or 16, as stored in the file
  bool hadAlpha = false;  ///< the file had an alpha channel (which is ignored)
  std::vector<float> rgb; ///< linear values (the sRGB transfer function undone)
};

/// Decodes the bytes of an 8- or 16-bit PNG or a JPEG (read with stb_image) whose values are
/// sRGB-encoded (grey images give equal channels; alpha is ignored; embedded gamma or ICC
/// profiles are not applied). Throws nx::Error naming `path` if the bytes are not such an
/// image or its buffers would not fit in memory.
LinearSrgbImage decodeSrgbImage(const std::string& bytes, const std::string& path);

/// A grey image's raw values: value[row * width + column], row 0 at the top.
struct GreyImage {
  int width = 0, height = 0;
  int bitsPerChannel = 8;   ///< 8 or 16
  std::vector<float> value; ///< the stored integers (0-255 or 0-65535), not linearised
};

/// Decodes an 8- or 16-bit PNG to its raw values (a colour PNG is reduced to one channel by
/// stb_image's luminance weights). Throws nx::Error naming `path` as decodeSrgbImage does.
GreyImage decodeGreyImage(const std::string& bytes, const std::string& path);

} // namespace nx
