#pragma once
// A scene tree (io/scene_tree.h) as scene text, one element per line, with the tree path of
// each line: the scene reader reads the text and names the path instead of the line in its
// errors ("objects[2].radius: expected a radius in (0, 1e+12], found '-1'"), so a scene from
// data is checked exactly as a file is. The mapping of a tree to elements and attributes is
// docs/python.md's "Scenes from data".

#include <string>
#include <vector>

#include "io/scene_tree.h"

namespace nx {

/// Scene text and the tree path of each of its lines (linePaths[line - 1]).
struct SceneTreeText {
  std::string text;
  std::vector<std::string> linePaths;
};

/// The scene text of a tree; throws nx::Error "path: expected ..., found ..." where the tree
/// has no scene form (a root key that is no section, an object without its "shape", a value of
/// no scene type).
SceneTreeText sceneTreeText(const SceneTree& root);

/// The scene text of one object (a dictionary with its "shape") or light alone in a <scene>,
/// its lines' paths under `path` ("objects[3]").
SceneTreeText itemTreeText(const SceneTree& item, bool light, const std::string& path);

} // namespace nx
