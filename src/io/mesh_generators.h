#pragma once
// Procedural meshes with shared vertices, so that closed shapes are watertight: every edge of a
// cube, icosphere or torus is shared by exactly two triangles that use the same two vertex indices.
#include "core/mesh.h"

namespace wideray {

/// The cube [-1,1]^3: 8 vertices, 12 triangles, counter-clockwise seen from outside. No normals
/// (its corners are shared by faces that point different ways).
TriangleMesh makeCube();

/// The unit square [-1,1] x [-1,1] in the xz plane at y = 0, facing +y: 4 vertices, 2 triangles.
TriangleMesh makeQuad();

/// A sphere of radius 1 made by splitting each triangle of an icosahedron into four,
/// `subdivisions` times (0..10): 10*4^s + 2 vertices, 20*4^s triangles, with smooth normals.
TriangleMesh makeIcosphere(int subdivisions);

/// A torus around the y axis: the tube's center circle has `majorRadius` and lies in the xz plane.
/// majorSegments*minorSegments vertices, twice as many triangles, smooth normals.
/// Requires 0 < minorRadius < majorRadius and at least 3 segments each way.
TriangleMesh makeTorus(float majorRadius, float minorRadius, int majorSegments, int minorSegments);

} // namespace wideray
