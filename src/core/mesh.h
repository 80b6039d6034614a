#pragma once
// An indexed triangle mesh as loaded from a file, before it is placed in a scene.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace wideray {

/// A material found in a mesh file (OBJ's MTL, glTF's PBR base color). The scene maps these by name.
struct MeshMaterial {
    std::string name;
    glm::vec3 diffuse{0.8f};
    /// OBJ map_Kd, glTF baseColorTexture (an image file of its own) as written, relative to the mesh
    /// file's folder; for an image inside the file, its name for messages ("model.glb:images[0].png").
    /// Empty: none.
    std::string diffuseTexture;
    /// The encoded image (PNG, JPEG) when it is inside the mesh file (a glTF data URI or buffer view).
    std::shared_ptr<const std::vector<unsigned char>> diffuseTextureBytes;
};

struct TriangleMesh {
    std::vector<glm::vec3> positions;
    std::vector<glm::vec3> normals;      ///< per vertex; empty or the size of positions
    std::vector<glm::vec2> uvs;          ///< per vertex; empty or the size of positions
    std::vector<glm::vec3> colors;       ///< per vertex, linear RGB (PLY colors); empty or the size of positions
    std::vector<glm::uvec3> triangles;   ///< vertex indices, all checked < positions.size()
    std::vector<uint32_t> faceMaterial;  ///< per triangle index into materials; empty = no materials
    std::vector<MeshMaterial> materials;
    size_t droppedDegenerate = 0;        ///< zero-area triangles removed while loading

    size_t triangleCount() const { return triangles.size(); }
};

} // namespace wideray
