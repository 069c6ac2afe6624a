#pragma once
// A scene description being edited by name (from Python, from a program building scenes): the
// description and the record of the edits made to it since it was read. The render key follows
// the description's state, not the record (sceneForRendering).

#include <cstdint>
#include <string>
#include <vector>

#include "integrators/scene_params/scene_fields.h"
#include "io/scene_desc.h"

namespace nx {

/// A description and its edits.
struct EditedScene {
  SceneDesc desc;
  std::vector<std::string> edits; ///< "objects[2].fluorescence.stokes_nm = 60", in order

  /// Records an edit: parameter (or list) `what` set to the value written `valueText`.
  void record(const std::string& what, const std::string& valueText) {
    edits.push_back(what + " = " + valueText);
  }
  /// Sets field parameter `name` (setSceneField) and records it as `valueText`.
  void setField(const std::string& name, const FieldValue& v, const std::string& valueText) {
    setSceneField(desc, name, v);
    record(name, valueText);
  }
};

/// The description to render: a copy with the digest of its state (a no-op edit, or 0.4 ->
/// 0.3 -> 0.4, keeps the file's key, and a scene edited into another file's state takes it).
SceneDesc sceneForRendering(const EditedScene& scene);

/// The edits as one attribute value ("a = 1; b = 2"; "" when there are none).
std::string editsText(const EditedScene& scene);

} // namespace nx
