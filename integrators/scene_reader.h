#pragma once
// Reading scenes with the registered kinds: the scene reader (io/scene_desc.h) is handed the
// shape, light, medium and material kinds' declarations from here, where the registries are
// (io/ depends on none of them, docs/architecture.md "Layers").

#include <string>
#include <variant>

#include "io/scene_desc.h"
#include "io/scene_kind_schemas.h"

namespace nx {

/// The registered kinds (accel/shape_kinds.h, integrators/lights/light_kinds.h,
/// integrators/media/medium_kinds.h, integrators/materials/material_kind.h) for the reader.
const SceneKindSchemas& registeredSceneKinds();

/// Reads a scene file with the registered kinds (io/scene_desc.h's loadScene).
SceneDesc loadScene(const std::string& path);

/// Parses scene text with the registered kinds; `file` names it in messages and anchors
/// relative paths.
SceneDesc parseScene(const std::string& text, const std::string& file);

/// Reads a scene given as data with the registered kinds (io/scene_desc.h's parseSceneTree).
SceneDesc parseSceneTree(const SceneTree& tree, const std::string& name);

/// One object or light given as data, with the registered kinds (io/scene_desc.h's
/// parseItemTree).
std::variant<ObjectDesc, LightDesc> parseItemTree(const SceneTree& item, bool light,
                                                  const std::string& path, const SceneDesc& scene);

} // namespace nx
