#include "integrators/scene_reader.h"

#include <string_view>

#include "accel/shape_kinds.h"
#include "integrators/lights/light_kinds.h"
#include "integrators/materials/material_kind.h"
#include "integrators/media/medium_kinds.h"

namespace nx {
namespace {

// The registries, as the reader sees them.
class RegisteredSceneKinds final : public SceneKindSchemas {
public:
  std::optional<ShapeKindSchema> shape(std::string_view name) const override {
    const ShapeKindSpec* k = findShapeKind(name);
    if (!k) return std::nullopt;
    return ShapeKindSchema{k->name, k->holdsMedium, k->params(), k->problem};
  }
  std::vector<std::string> shapeNames() const override {
    std::vector<std::string> names;
    for (const ShapeKindSpec& k : shapeKinds()) names.emplace_back(k.name);
    return names;
  }
  std::optional<TakenKindSchema> light(std::string_view name) const override {
    const LightKindSpec* k = findLightKind(name);
    if (!k) return std::nullopt;
    return TakenKindSchema{k->name, k->params()};
  }
  std::optional<TakenKindSchema> medium(std::string_view name) const override {
    const MediumKindSpec* k = findMediumKind(name);
    if (!k) return std::nullopt;
    return TakenKindSchema{k->name, k->params()};
  }
  bool isMaterial(std::string_view name) const override {
    return findMaterialKind(name) != nullptr;
  }
  void checkMaterial(std::string_view kind, const ParameterSet& params) const override {
    checkMaterialParameters(*findMaterialKind(kind), params);
  }
  std::string shapeList() const override { return shapeKindList(); }
  std::string lightList() const override { return lightKindList(); }
  std::string mediumList() const override { return mediumKindList(); }
  std::string materialList() const override { return materialKindList(); }
};

} // namespace

const SceneKindSchemas& registeredSceneKinds() {
  static const RegisteredSceneKinds kinds;
  return kinds;
}

SceneDesc loadScene(const std::string& path) {
  return loadScene(path, registeredSceneKinds());
}

SceneDesc parseScene(const std::string& text, const std::string& file) {
  return parseScene(text, file, registeredSceneKinds());
}

SceneDesc parseSceneTree(const SceneTree& tree, const std::string& name) {
  return parseSceneTree(tree, name, registeredSceneKinds());
}

std::variant<ObjectDesc, LightDesc> parseItemTree(const SceneTree& item, bool light,
                                                  const std::string& path, const SceneDesc& scene) {
  return parseItemTree(item, light, path, scene, registeredSceneKinds());
}

} // namespace nx
