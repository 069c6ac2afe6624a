#pragma once
// What the scene reader must know of the kinds a scene can name: their names and the
// parameters each takes. The scene format writes values without types (<radius>2</radius>),
// so reading one needs its kind's declaration; the reader is handed the declarations through
// this interface by the layer that registers the kinds (integrators/scene_reader.h), so io/
// depends on no registry and the kinds are resolved where they are built.

#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "core/params/parameter_set.h"
#include "core/params/shape_parameter.h"

namespace nx {

/// A shape kind as the reader sees it: its element name and parameters.
struct ShapeKindSchema {
  const char* name;                                            ///< its element name (<sphere>)
  bool holdsMedium;                                            ///< it can hold a <medium>
  std::span<const ShapeParameter> params;                      ///< the parameters it takes
  std::optional<ShapeProblem> (*problem)(const ParameterSet&); ///< why they make no shape
};

/// A light or medium kind as the reader sees it: its type="..." name and parameters.
struct TakenKindSchema {
  const char* name;                       ///< as written in type="..."
  std::span<const TakenParameter> params; ///< the parameters it takes
};

/// The kinds a scene can name, for the reader.
class SceneKindSchemas {
public:
  virtual ~SceneKindSchemas() = default;
  /// The shape kind whose element is <name>, if any.
  virtual std::optional<ShapeKindSchema> shape(std::string_view name) const = 0;
  /// Every shape kind's element name, in the order lists of them are written.
  virtual std::vector<std::string> shapeNames() const = 0;
  /// The light kind called `name`, if any.
  virtual std::optional<TakenKindSchema> light(std::string_view name) const = 0;
  /// The medium kind called `name`, if any.
  virtual std::optional<TakenKindSchema> medium(std::string_view name) const = 0;
  /// Whether `name` is a material kind.
  virtual bool isMaterial(std::string_view name) const = 0;
  /// Throws nx::Error at the first of `params` that material kind `kind` does not take.
  virtual void checkMaterial(std::string_view kind, const ParameterSet& params) const = 0;
  /// "a, b, ... or z": the kinds' names for messages.
  virtual std::string shapeList() const = 0;
  /// "a, b, ... or z": the light kinds' names for messages.
  virtual std::string lightList() const = 0;
  /// "a, b, ... or z": the medium kinds' names for messages.
  virtual std::string mediumList() const = 0;
  /// "a, b, ... or z": the material kinds' names for messages.
  virtual std::string materialList() const = 0;
};

} // namespace nx
