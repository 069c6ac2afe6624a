#pragma once
// Reflectance textures from image files: a spectral EXR in the project's layout checked to hold
// reflectances (bands sorted by wavelength), or an sRGB PNG/JPEG upsampled per texel through
// the sigmoid table (Jakob & Hanika 2019).

#include <memory>
#include <string>

#include "spectra/reflectance_texture.h"

namespace nx {

/// The texture in `path` (by its extension: .exr spectral, else PNG/JPEG); `bytes` is the
/// file's content, read by the caller (who folds it into the render key); holdEnds: a spectral
/// one holds its end bands beyond them (else 0 there). Throws nx::Error naming the file.
std::shared_ptr<const ReflectanceTexture>
readReflectanceTexture(const std::string& path, const std::string& bytes, bool holdEnds = false);

} // namespace nx
