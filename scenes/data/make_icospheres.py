#!/usr/bin/env python3
"""Writes icosphere_flat.ply and icosphere_smooth.ply: a unit icosphere (an icosahedron whose
triangles are split in four twice, 320 triangles, vertices projected onto the sphere), without
normals (flat shading) and with vertex normals. Run from this folder."""
import math

GOLDEN = (1 + 5 ** 0.5) / 2
CORNERS = [(-1, GOLDEN, 0), (1, GOLDEN, 0), (-1, -GOLDEN, 0), (1, -GOLDEN, 0),
           (0, -1, GOLDEN), (0, 1, GOLDEN), (0, -1, -GOLDEN), (0, 1, -GOLDEN),
           (GOLDEN, 0, -1), (GOLDEN, 0, 1), (-GOLDEN, 0, -1), (-GOLDEN, 0, 1)]
FACES = [(0, 11, 5), (0, 5, 1), (0, 1, 7), (0, 7, 10), (0, 10, 11), (1, 5, 9), (5, 11, 4),
         (11, 10, 2), (10, 7, 6), (7, 1, 8), (3, 9, 4), (3, 4, 2), (3, 2, 6), (3, 6, 8),
         (3, 8, 9), (4, 9, 5), (2, 4, 11), (6, 2, 10), (8, 6, 7), (9, 8, 1)]


def unit(p):
    length = math.sqrt(sum(x * x for x in p))
    return tuple(x / length for x in p)


def icosphere(levels):
    vertices = [unit(p) for p in CORNERS]
    faces = FACES
    for _ in range(levels):
        middles = {}

        def middle(a, b):
            key = (min(a, b), max(a, b))
            if key not in middles:
                vertices.append(unit([(vertices[a][i] + vertices[b][i]) / 2 for i in range(3)]))
                middles[key] = len(vertices) - 1
            return middles[key]

        split = []
        for a, b, c in faces:
            ab, bc, ca = middle(a, b), middle(b, c), middle(c, a)
            split += [(a, ab, ca), (b, bc, ab), (c, ca, bc), (ab, bc, ca)]
        faces = split
    return vertices, faces


def write(name, vertices, faces, normals):
    with open(name, "w") as out:
        out.write("ply\nformat ascii 1.0\n")
        out.write(f"comment unit icosphere, icosahedron subdivided twice ({len(faces)} triangles), "
                  + ("vertex normals" if normals else "no normals (flat shading)")
                  + "; written by scenes/data/make_icospheres.py\n")
        out.write(f"element vertex {len(vertices)}\nproperty float x\nproperty float y\n"
                  "property float z\n")
        if normals:
            out.write("property float nx\nproperty float ny\nproperty float nz\n")
        out.write(f"element face {len(faces)}\nproperty list uchar int vertex_indices\n"
                  "end_header\n")
        for p in vertices:
            values = list(p) + (list(p) if normals else [])
            out.write(" ".join("%.7f" % x for x in values) + "\n")
        for a, b, c in faces:
            out.write(f"3 {a} {b} {c}\n")


if __name__ == "__main__":
    v, f = icosphere(2)
    write("icosphere_flat.ply", v, f, False)
    write("icosphere_smooth.ply", v, f, True)
