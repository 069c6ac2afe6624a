#pragma once
// What a shape kind declares and needs: its parameters (each with its type, unit, range and
// meaning: the scene loader reads them by it), the checks its values must pass, and what its
// build asks of the scene. A kind is one header of accel/kinds/ (its primitive, intersection,
// parameters and build); the registry (accel/shape_kinds.h) lists the kinds.

#include <optional>
#include <span>
#include <string>

#include "core/params/parameter_set.h"

namespace nx {

class TriangleMesh; // core/triangle_mesh.h

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

/// What a shape kind's build asks of the scene; implemented by the scene builder, called once
/// per shape, never while rendering.
class ShapeInputs {
public:
  virtual ~ShapeInputs() = default;
  /// A mesh file read and transformed (its bytes join the render key); throws nx::Error naming
  /// the file and the problem.
  virtual TriangleMesh meshFile(const std::string& path, const AffineDesc& transform) const = 0;
  /// Notes a warning about the shape being built (the object's file:line is put before it).
  virtual void warn(const std::string& message) const = 0;
};

} // namespace nx
