#pragma once
// A scene description as a scene tree (io/scene_tree.h): what Scene.to_dict gives and, written
// by io/scene_tree_text.h, what Scene.to_text gives. Read back (parseSceneTree, parseScene) it
// is the same scene state (sceneStateText), so it renders bit for bit the same.

#include <string>

#include "io/scene_desc.h"
#include "io/scene_tree.h"

namespace nx {

/// The tree of `d`. File names are written relative to the directory `base` when it is given
/// (where the text will be read from), else as the description holds them. Throws nx::Error
/// naming the item ("objects[1].reflectance: ...") for a value given from Python as numbers
/// that has no scene-text form (a texture, a measured matrix, a concentration map: write them
/// to files and name the files).
SceneTree sceneToTree(const SceneDesc& d, const std::string& base = "");

/// The tree of one object or light of a scene (what sceneToTree lists), `where` naming it in
/// errors.
SceneTree objectToTree(const ObjectDesc& o, const std::string& where);
SceneTree lightToTree(const LightDesc& l, const std::string& where);

/// The scene text of `d` (sceneTreeText of sceneToTree).
std::string sceneToText(const SceneDesc& d, const std::string& base = "");

} // namespace nx
