#include "integrators/scene_params/edited_scene.h"

#include "io/scene_state_text.h"

namespace nx {

SceneDesc sceneForRendering(const EditedScene& scene) {
  SceneDesc d = scene.desc;
  d.textDigest = sceneStateDigest(d);
  return d;
}

std::string editsText(const EditedScene& scene) {
  std::string out;
  for (const std::string& e : scene.edits) out += (out.empty() ? "" : "; ") + e;
  return out;
}

} // namespace nx
