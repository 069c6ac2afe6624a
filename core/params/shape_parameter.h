#pragma once
// What a shape kind's parameter is (beyond its ParamSpec) and why parameters together make no
// shape: the shape kinds (accel/kinds/) declare their parameters with it, and the scene reader
// (io/) reads them by it without knowing the kinds (io/scene_kind_schemas.h).

#include <string>

#include "core/params/parameter_set.h"

namespace nx {

/// One parameter a shape kind takes.
struct ShapeParameter {
  ParamSpec spec;         ///< name, type, unit, range, meaning, example
  bool required = true;   ///< the shape cannot be built without it
  bool attribute = false; ///< written as an attribute (<mesh file="...">), not as a child
  /// What a value must be beyond its type and range (null: nothing); returns the "expected"
  /// phrase of the error for a value that is not (e.g. "a non-zero plane normal"), else null.
  const char* (*valueProblem)(const ParamValue&) = nullptr;
};

/// Why a shape's parameters together describe no shape: the error's "expected" and "found".
struct ShapeProblem {
  std::string expected, found;
};

} // namespace nx
