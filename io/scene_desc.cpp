#include "io/scene_desc.h"

namespace nx {

void removeFluorescence(SceneDesc& desc) {
  for (auto& o : desc.objects) o.params.erase("fluorescence");
  for (auto& m : desc.materials) m.material.params.erase("fluorescence");
}

} // namespace nx
