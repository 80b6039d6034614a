#include "core/scene.h"

namespace wideray {

TriangleMesh flattenTriangles(const Scene& scene) {
    size_t vertexCount = 0, triangleCount = 0;
    bool anyNormals = false, anyUvs = false;
    for (const MeshInstance& instance : scene.instances) {
        const TriangleMesh& mesh = scene.meshes.at(instance.mesh);
        vertexCount += mesh.positions.size();
        triangleCount += mesh.triangles.size();
        anyNormals = anyNormals || !mesh.normals.empty();
        anyUvs = anyUvs || !mesh.uvs.empty();
    }

    TriangleMesh world;
    world.positions.reserve(vertexCount);
    world.triangles.reserve(triangleCount);
    world.faceMaterial.reserve(triangleCount);
    if (anyNormals) world.normals.reserve(vertexCount);
    if (anyUvs) world.uvs.reserve(vertexCount);

    for (const MeshInstance& instance : scene.instances) {
        const TriangleMesh& mesh = scene.meshes[instance.mesh];
        const uint32_t firstVertex = uint32_t(world.positions.size());
        const glm::mat3 normalTransform = glm::transpose(glm::inverse(glm::mat3(instance.transform)));
        // A mirroring transform turns counter-clockwise triangles clockwise; swapping two corners
        // keeps the winding (and so the geometric normal) pointing outward.
        const bool mirrored = glm::determinant(glm::mat3(instance.transform)) < 0.0f;

        for (const glm::vec3& p : mesh.positions) world.positions.push_back(glm::vec3(instance.transform * glm::vec4(p, 1.0f)));
        // Meshes without normals get zero normals, which mean "use the geometric normal" (flat shading).
        if (anyNormals) {
            if (mesh.normals.empty()) world.normals.resize(world.positions.size(), glm::vec3(0.0f));
            for (const glm::vec3& n : mesh.normals) world.normals.push_back(glm::normalize(normalTransform * n));
        }
        if (anyUvs) {
            if (mesh.uvs.empty()) world.uvs.resize(world.positions.size(), glm::vec2(0.0f));
            world.uvs.insert(world.uvs.end(), mesh.uvs.begin(), mesh.uvs.end());
        }
        for (size_t t = 0; t < mesh.triangles.size(); ++t) {
            const glm::uvec3 tri = mesh.triangles[t] + firstVertex;
            world.triangles.push_back(mirrored ? glm::uvec3(tri.x, tri.z, tri.y) : tri);
            // Meshes built in code may carry no materials; they use the scene's first material.
            const uint32_t material = instance.material != MeshInstance::kMeshMaterials ? instance.material
                                      : mesh.faceMaterial.empty()                        ? 0
                                                                                         : mesh.faceMaterial[t];
            world.faceMaterial.push_back(material);
        }
        world.droppedDegenerate += mesh.droppedDegenerate;
    }
    return world;
}

} // namespace wideray
