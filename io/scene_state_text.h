#pragma once
// A scene description's state as one canonical text: every value that changes what renders,
// in a fixed order, numbers with 17 digits, without the file:line locations. Two descriptions
// with the same text render the same (the render key of an edited scene is made from it, so
// that 0.4 -> 0.3 -> 0.4 or a no-op edit keeps the file's key).

#include <cstdint>
#include <string>

#include "io/scene_desc.h"

namespace nx {

/// The canonical text of `d`'s state (settings, camera, lights, objects, named spectra and
/// materials; not its warnings, its locations or its digest).
std::string sceneStateText(const SceneDesc& d);

/// FNV-1a of sceneStateText: what a scene contributes to the render key before its referenced
/// files' bytes are folded in (SceneDesc::textDigest).
uint64_t sceneStateDigest(const SceneDesc& d);

} // namespace nx
