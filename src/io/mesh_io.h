#pragma once
// Loading triangle meshes from OBJ, PLY and glTF 2.0 files.
#include <filesystem>

#include "core/mesh.h"

namespace wideray {

/// Loads a mesh, choosing the format from the extension (.obj, .ply, .gltf, .glb). Polygons are
/// fan-triangulated; zero-area triangles are dropped and counted in `droppedDegenerate`.
/// Throws InputError naming the file, the line (or byte offset / glTF element) and what is wrong:
/// a missing file, truncated data, an out-of-range index, NaN or Inf coordinates.
TriangleMesh loadMesh(const std::filesystem::path& path);

TriangleMesh loadObj(const std::filesystem::path& path);
TriangleMesh loadPly(const std::filesystem::path& path);
TriangleMesh loadGltf(const std::filesystem::path& path);

/// The same from memory (the fuzzing harnesses' entry points): `file` names the data in messages.
/// OBJ: every mtllib reads `mtlText`. glTF: binary (GLB) when the data starts with its magic "glTF";
/// external buffers and images are looked up next to `file`.
TriangleMesh parseObj(const std::string& objText, const std::string& mtlText, const std::string& file);
TriangleMesh parsePly(const std::string& data, const std::string& file);
TriangleMesh parseGltf(const std::string& data, const std::string& file);

/// Removes zero-area triangles (and counts them); checks indices and coordinates. Shared by every loader.
void validateMesh(TriangleMesh& mesh, const std::string& file);

/// Empty when the mesh bounds a solid: vertices welded by position, every edge is used once in each
/// direction (a closed, consistently oriented surface). Otherwise what is wrong, naming an edge.
std::string closedSurfaceDefect(const TriangleMesh& mesh);

} // namespace wideray
