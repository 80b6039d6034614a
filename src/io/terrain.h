#pragma once
// Fractal terrain: Musgrave's ridged multifractal (Ebert et al., "Texturing and Modeling", ch. 16)
// sampled on a regular grid over [-1, 1]^2, as heights for the height-field primitive and as the
// same surface triangulated (generated shape "terrain").
#include <cstdint>
#include <vector>

#include "core/mesh.h"
#include "core/scene.h"

namespace wideray {


/// The (resolution + 1)^2 heights, row by row in z (x fastest), vertex (i, j) at
/// x = -1 + 2 i / resolution, z = -1 + 2 j / resolution.
std::vector<float> ridgedMultifractalHeights(const TerrainParameters& p);

/// A height field over [-1, 1]^2; each cell split into two triangles along its (i, j)-(i+1, j+1) diagonal.
TriangleMesh heightFieldMesh(const std::vector<float>& heights, int resolution);

} // namespace wideray
