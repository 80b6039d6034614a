#pragma once
/// Reading a triangle mesh from an OBJ, PLY or glTF/GLB file into arrays Scene::addTriangleMesh takes.
#include <cstdint>
#include <string>
#include <vector>

#include "wideray/export.h"

namespace wideray {

struct MeshArrays {
    std::vector<float> positions;   ///< x, y, z per vertex
    std::vector<uint32_t> indices;  ///< 3 vertex indices per triangle
};

/// The format comes from the extension (.obj, .ply, .gltf, .glb); polygons are fan-triangulated,
/// zero-area triangles dropped. Throws wideray::Error naming the file, the place and what is wrong.
WIDERAY_API MeshArrays loadMeshFile(const std::string& path);

} // namespace wideray
