#pragma once
// The shape kinds a scene's object elements can name (<sphere>, <plane>, ...): their specs,
// generated from one list of the kinds' headers, and the analytic primitives' types, generated
// from NX_ANALYTIC_PRIMITIVES (accel/shape_kind.h). A kind's build gives one primitive of
// ShapeGeometry, which the scene builder places in the geometry (GeometryScene dispatches on
// the primitive, statically, while rendering). Adding a kind: its header in kinds/ and its name
// in ShapeKindList below; a new analytic primitive also its line in NX_ANALYTIC_PRIMITIVES
// (docs/architecture.md).

#include <cctype>
#include <cstdlib>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <tuple>
#include <utility>
#include <variant>
#include <vector>

#include "accel/kinds/box.h"
#include "accel/kinds/capsule.h"
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
using ShapeKindList =
    std::tuple<SphereShapeKind, PlaneShapeKind, TriangleShapeKind, QuadShapeKind, MeshShapeKind,
               BoxShapeKind, DiskShapeKind, CylinderShapeKind, CapsuleShapeKind>;

/// A list of primitive types.
template <class... P>
struct PrimitiveTypes {};

namespace detail {
template <class First, class... Rest>
struct AfterFirst {
  using type = PrimitiveTypes<Rest...>;
};
template <class Types, class... Others>
struct VariantOf;
template <class... P, class... Others>
struct VariantOf<PrimitiveTypes<P...>, Others...> {
  using type = std::variant<Others..., P...>;
};
template <class P>
constexpr bool kNotAnAnalyticPrimitive = false;
} // namespace detail

#define NX_PRIMITIVE_TYPE(Name) , Name##Shape
/// The analytic primitives' types (NameShape of each NX_ANALYTIC_PRIMITIVES line), in order.
using AnalyticPrimitives = detail::AfterFirst<void NX_ANALYTIC_PRIMITIVES(NX_PRIMITIVE_TYPE)>::type;
#undef NX_PRIMITIVE_TYPE

/// The ShapeKind of analytic primitive type P.
template <class P>
inline constexpr ShapeKind kShapeKindOf = [] {
  static_assert(detail::kNotAnAnalyticPrimitive<P>, "not in NX_ANALYTIC_PRIMITIVES");
  return ShapeKind::Plane;
}();
#define NX_SHAPE_KIND_OF(Name)                                                                     \
  template <>                                                                                      \
  inline constexpr ShapeKind kShapeKindOf<Name##Shape> = ShapeKind::Name;                          \
  static_assert(AnalyticPrimitive<Name##Shape>, #Name "Shape lacks a member AnalyticPrimitive "    \
                                                      "asks for (accel/primitive.h)");
NX_ANALYTIC_PRIMITIVES(NX_SHAPE_KIND_OF)
#undef NX_SHAPE_KIND_OF

/// True for the kinds of analytic primitives (not planes, not triangles).
constexpr bool isAnalytic(ShapeKind kind) {
  return kind != ShapeKind::Plane && kind != ShapeKind::Triangle;
}

#define NX_VISIT_PRIMITIVE_CASE(Name)                                                              \
  case ShapeKind::Name:                                                                            \
    return visit.template operator()<Name##Shape>();
/// visit.template operator()<P>() for the analytic primitive type P of `kind` (the one switch
/// over primitive kinds, generated). `kind` must be analytic (isAnalytic).
template <class Visit>
decltype(auto) visitAnalyticKind(ShapeKind kind, Visit&& visit) {
  switch (kind) {
    NX_ANALYTIC_PRIMITIVES(NX_VISIT_PRIMITIVE_CASE)
  case ShapeKind::Plane:
  case ShapeKind::Triangle:
    break;
  }
  std::abort(); // a plane or a triangle: callers ask isAnalytic first
}
#undef NX_VISIT_PRIMITIVE_CASE

#define NX_PRIMITIVE_NAME(Name) #Name,
/// The lower-case name of an analytic primitive's kind ("sphere", "disk", ...), for messages.
inline std::string primitiveName(ShapeKind kind) {
  static constexpr const char* kNames[] = {"plane", "triangle",
                                           NX_ANALYTIC_PRIMITIVES(NX_PRIMITIVE_NAME)};
  std::string name = kNames[static_cast<size_t>(kind)];
  for (char& c : name) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return name;
}
#undef NX_PRIMITIVE_NAME

/// Calls visit.template operator()<P>() for every analytic primitive type P, in list order.
template <class Visit>
void forEachAnalyticKind(Visit&& visit) {
  [&]<class... P>(PrimitiveTypes<P...>) {
    (visit.template operator()<P>(), ...);
  }(AnalyticPrimitives{});
}

namespace detail {
template <class Types>
struct VectorsOf;
template <class... P>
struct VectorsOf<PrimitiveTypes<P...>> {
  using type = std::tuple<std::vector<P>...>;
};
} // namespace detail

/// One vector per analytic primitive type: a scene's spheres, disks, cylinders, ...
using AnalyticShapes = detail::VectorsOf<AnalyticPrimitives>::type;

/// Fills a hit's uv where its primitive left them for later (uvPending: a sphere's), so that
/// untextured surfaces do not pay for them.
inline void surfaceUv(SurfaceHit& hit) {
  if (!hit.uvPending) return;
  visitAnalyticKind(hit.kind, [&]<class P>() {
    if constexpr (requires { P::lazyUv(hit); }) P::lazyUv(hit);
  });
  hit.uvPending = false;
}

/// What a shape kind's build gives: a primitive the geometry holds.
using ShapeGeometry =
    detail::VariantOf<AnalyticPrimitives, PlaneShape, TriangleShape, TriangleMesh>::type;

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
