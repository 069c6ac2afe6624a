#pragma once
// What a shape kind declares and needs: its parameters (each with its type, unit, range and
// meaning: the scene loader reads them by it), the checks its values must pass, and what its
// build asks of the scene. A kind is one header of accel/kinds/ (its primitive, intersection,
// parameters and build); the registry (accel/shape_kinds.h) lists the kinds.

#include <optional>
#include <span>
#include <string>

#include "core/params/shape_parameter.h"

namespace nx {

class TriangleMesh; // core/triangle_mesh.h

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
