#pragma once
// The geometry last built (its Embree device and BVH), shared by the next render of the very
// same shapes: a program that renders many scenes differing only in camera, materials or
// lights (a Python dataset loop, a relighting sweep) builds the BVH once.

#include <memory>
#include <vector>

#include "accel/geometry_scene.h"

namespace nx {

/// The geometry of these shapes: the one last built when its analytic primitives, planes and
/// meshes are equal to these (compared exactly, every coordinate and index), else built now.
/// A build first drops the one kept before, so no two geometries are held at once on its account.
/// Geometries over a quarter of the memory budget are not kept.
std::shared_ptr<const GeometryScene> sharedGeometry(AnalyticShapes analytic,
                                                    std::vector<PlaneShape> planes,
                                                    std::vector<TriangleMesh> meshes);

/// sharedGeometry of spheres, planes and meshes only.
std::shared_ptr<const GeometryScene> sharedGeometry(std::vector<SphereShape> spheres,
                                                    std::vector<PlaneShape> planes,
                                                    std::vector<TriangleMesh> meshes);

/// Drops the geometry kept for the next render (renders still holding it keep it alive).
void clearGeometryCache();

/// How many geometries sharedGeometry built since the program started (tests).
size_t geometriesBuilt();

} // namespace nx
