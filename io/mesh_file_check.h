#pragma once
// Structural checks of PLY and OBJ files before a parser library sees them.
//
// Assimp 5.2 loops forever on an ASCII PLY whose body ends early and reports a misleading
// "vertex index out of range" for an OBJ vertex with a non-number; these checks find such
// problems first and name the line (ASCII) or the element and byte offset (binary).

#include <cstdint>
#include <string>

namespace nx {

/// What a mesh file's check counted: its vertices and faces (polygons, before triangulation).
struct MeshFileCounts {
  uint64_t vertices = 0, faces = 0;
};

/// Throws nx::Error "<path>:<line>: ..." (ASCII) or "<path>: ..." (binary) unless `bytes` is a
/// PLY file with a valid header in printable ASCII (format, elements, properties named once), one
/// vertex element with scalar x, y, z, one face element with one integer vertex index list, and
/// a body holding every element item: ASCII items with exactly their properties' numbers
/// (plain decimals, whole where integers), faces of at least 3 vertices that exist; binary
/// bodies holding every declared item (a cut at an item boundary is a truncation), with vertex
/// indices that exist.
MeshFileCounts checkPlyFile(const std::string& bytes, const std::string& path);

/// Throws nx::Error "<path>:<line>: ..." unless every statement of the OBJ text is known, starts
/// its line and holds no control byte, with plain decimal numbers (v: 3, 4 or 6; vt: 1 to 3;
/// vn: 3), faces of at least 3, lines of 2 and points of 1 vertex references that exist
/// (1-based, or negative: relative to the vertices read so far), and some face exists.
MeshFileCounts checkObjFile(const std::string& bytes, const std::string& path);

} // namespace nx
