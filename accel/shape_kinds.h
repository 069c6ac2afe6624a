#pragma once
// The shape kinds a scene's object elements can name (<sphere>, <plane>, ...): their specs,
// generated from one list of the kinds' headers. A kind's build gives one primitive of
// ShapeGeometry, which the scene builder places in the geometry (GeometryScene dispatches on
// the primitive, statically, while rendering). Adding a kind: its header in kinds/ and its name
// in ShapeKindList below, plus a ShapeGeometry alternative if its primitive is new
// (docs/architecture.md).

#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <tuple>
#include <utility>
#include <variant>
#include <vector>

#include "accel/kinds/box.h"
#include "accel/kinds/cylinder.h"
#include "accel/kinds/disk.h"
#include "accel/kinds/mesh.h"
#include "accel/kinds/plane.h"
#include "accel/kinds/quad.h"
#include "accel/kinds/sphere.h"
#include "accel/kinds/triangle.h"
#include "core/kind_lookup.h"

namespace nx {

/// The registered shape kinds, in the order the reference docs list them.
using ShapeKindList = std::tuple<SphereShapeKind, PlaneShapeKind, TriangleShapeKind, QuadShapeKind,
                                 MeshShapeKind, BoxShapeKind, DiskShapeKind, CylinderShapeKind>;

/// What a shape kind's build gives: a primitive the geometry holds.
using ShapeGeometry =
    std::variant<SphereShape, PlaneShape, TriangleShape, TriangleMesh, DiskShape, CylinderShape>;

/// A shape kind as the scene format sees it.
struct ShapeKindSpec {
  const char* name;                                            ///< its element name (<sphere>)
  const char* doc;                                             ///< one line for the reference docs
  bool holdsMedium;                                            ///< it can hold a <medium>
  std::span<const ShapeParameter> (*params)();                 ///< the parameters it takes
  std::optional<ShapeProblem> (*problem)(const ParameterSet&); ///< why they make no shape
  ShapeGeometry (*build)(const ParameterSet&, const ShapeInputs&); ///< from checked parameters
};

namespace detail {
template <class Kind>
ShapeKindSpec shapeKindSpec() {
  return {Kind::kName,
          Kind::kDoc,
          Kind::kHoldsMedium,
          &Kind::parameters,
          &Kind::problem,
          [](const ParameterSet& p, const ShapeInputs& in) -> ShapeGeometry {
            return Kind::build(p, in);
          }};
}
template <size_t... I>
std::array<ShapeKindSpec, sizeof...(I)> shapeKindSpecs(std::index_sequence<I...>) {
  return {shapeKindSpec<std::tuple_element_t<I, ShapeKindList>>()...};
}
} // namespace detail

/// Every shape kind, in ShapeKindList's order.
inline std::span<const ShapeKindSpec> shapeKinds() {
  static const auto specs =
      detail::shapeKindSpecs(std::make_index_sequence<std::tuple_size_v<ShapeKindList>>());
  return specs;
}

/// The kind called `name`, or null.
inline const ShapeKindSpec* findShapeKind(std::string_view name) {
  return findKindNamed(shapeKinds(), name);
}

/// "sphere, plane, ... or mesh": the kinds' names for messages.
inline std::string shapeKindList() {
  return kindNameList(shapeKinds());
}

/// The declaration of parameter `name` of `kind`, or null.
inline const ShapeParameter* shapeParameter(const ShapeKindSpec& kind, std::string_view name) {
  return findParameterNamed(kind.params(), name);
}

/// Why a shape's parameters (each already of its type and within its range) describe no
/// shape of `kind`: a required one missing, a value's own check, or the kind's check of them
/// together; nullopt if they describe one.
inline std::optional<ShapeProblem> shapeProblem(const ShapeKindSpec& kind, const ParameterSet& p) {
  for (const ShapeParameter& sp : kind.params()) {
    const Parameter* v = p.find(sp.spec.name);
    if (!v) {
      if (sp.required)
        return ShapeProblem{"<" + std::string(sp.spec.name) + "> on a " + kind.name, "none"};
      continue;
    }
    if (sp.valueProblem)
      if (const char* expected = sp.valueProblem(v->value)) {
        const Vec3d* x = std::get_if<Vec3d>(&v->value);
        return ShapeProblem{expected,
                            x ? numberText(x->x) + ", " + numberText(x->y) + ", " + numberText(x->z)
                              : std::string("the value given")};
      }
  }
  return kind.problem(p);
}

} // namespace nx
