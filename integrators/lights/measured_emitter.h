#pragma once
// A lamp as measured, on an area emitter: the spectral irradiance it gives on its axis at a
// distance, or its total radiant flux, turned into the radiance of its shape (two-sided
// Lambertian emitters; docs/lights.md, "Lamps as measured").

#include <string>

#include "accel/shape_kinds.h"

namespace nx {

/// Projected solid angle of triangle t seen from x with unit normal n (the irradiance of a
/// triangle of radiance 1 wholly above x's horizon): Lambert's contour formula, half the sum
/// over edges of the angle the edge subtends times n . the unit normal of its plane with x.
double projectedSolidAngle(const TriangleShape& t, const Vec3d& x, const Vec3d& n);

/// Irradiance / radiance on the emitter's axis at distance d, the receiver facing it: a
/// sphere's pi R^2 / d^2 (d > R, any direction from its centre); a flat emitter's (a
/// triangle, a quad, a planar mesh) projected solid angle seen from centroid + d * normal, by
/// Lambert's contour formula (Arvo 1995, eq. 2): sum over edges of theta_e (Gamma_e . n) / 2.
/// Throws nx::Error "expected ..., found ..." (prefixed by `where`) for a plane, a curved mesh
/// (no axis) or d inside the sphere.
double axialIrradiancePerRadiance(const ShapeGeometry& g, double d, const std::string& where);

/// Total radiant flux / radiance of the emitter: a sphere's outward 4 pi^2 R^2; a triangle's,
/// quad's or open mesh's 2 pi A (both faces emit); a closed mesh's pi A (its inward light
/// never leaves). Throws nx::Error for a plane (infinite).
double fluxPerRadiance(const ShapeGeometry& g, const std::string& where);

} // namespace nx
