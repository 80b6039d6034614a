#include "geometry/triangle_geometry.h"

#include <algorithm>
#include <cstdint>

#include "core/error.h"

namespace wideray {

namespace {

bool flattened(const std::vector<bool>& twoLevel, const MeshInstance& instance) {
    return twoLevel.empty() || !twoLevel.at(instance.mesh);
}

} // namespace

TriangleMesh flattenTriangles(const SceneDescription& scene, const std::vector<bool>& twoLevel) {
    size_t vertexCount = 0, triangleCount = 0;
    bool anyNormals = false, anyUvs = false, anyColors = false;
    for (const MeshInstance& instance : scene.instances) {
        if (!flattened(twoLevel, instance)) continue;
        const TriangleMesh& mesh = scene.meshes.at(instance.mesh);
        vertexCount += mesh.positions.size();
        triangleCount += mesh.triangles.size();
        anyNormals = anyNormals || !mesh.normals.empty();
        if (vertexCount > UINT32_MAX || triangleCount > UINT32_MAX)
            throw InputError(scene.file.string(), "", "the flattened instances have more than 2^32 - 1 vertices or triangles; "
                                                      "trace them two-level (--instancing two-level or auto)");
        anyUvs = anyUvs || !mesh.uvs.empty();
        anyColors = anyColors || !mesh.colors.empty();
    }

    TriangleMesh world;
    world.positions.reserve(vertexCount);
    world.triangles.reserve(triangleCount);
    world.faceMaterial.reserve(triangleCount);
    if (anyNormals) world.normals.reserve(vertexCount);
    if (anyUvs) world.uvs.reserve(vertexCount);
    if (anyColors) world.colors.reserve(vertexCount);

    for (const MeshInstance& instance : scene.instances) {
        if (!flattened(twoLevel, instance)) continue;
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
        if (anyColors) {  // meshes without colors are white: their materials as they are
            if (mesh.colors.empty()) world.colors.resize(world.positions.size(), glm::vec3(1.0f));
            world.colors.insert(world.colors.end(), mesh.colors.begin(), mesh.colors.end());
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

TriangleGeometry::TriangleGeometry(const SceneDescription& scene, const std::vector<bool>& twoLevel)
    : world_(flattenTriangles(scene, twoLevel)) {
    uint32_t first = 0;
    for (uint32_t i = 0; i < scene.instances.size(); ++i) {
        if (!flattened(twoLevel, scene.instances[i])) continue;
        instanceFirst_.push_back(first);
        instanceIds_.push_back(i);
        first += uint32_t(scene.meshes[scene.instances[i].mesh].triangles.size());
    }
}

TriangleGeometry::TriangleGeometry(TriangleMesh mesh) : world_(std::move(mesh)), instanceFirst_{0}, instanceIds_{0} {}

Bounds3f TriangleGeometry::primitiveBounds(uint32_t primId) const {
    const glm::uvec3& t = world_.triangles[primId];
    Bounds3f b;
    b.grow(world_.positions[t.x]);
    b.grow(world_.positions[t.y]);
    b.grow(world_.positions[t.z]);
    return b;
}

Bounds3f TriangleGeometry::bounds() const {
    Bounds3f b;
    for (const glm::vec3& p : world_.positions) b.grow(p);
    return b;
}

size_t TriangleGeometry::slotOf(uint32_t primId) const {
    // Instances of empty meshes share a start; the last of them owns the triangles that follow.
    auto it = std::upper_bound(instanceFirst_.begin(), instanceFirst_.end(), primId);
    return size_t(it - instanceFirst_.begin()) - 1;
}

SurfacePoint TriangleGeometry::surface(const Ray&, const Hit& hit) const {
    const glm::uvec3& tri = world_.triangles[hit.primId];
    const glm::vec3 &a = world_.positions[tri.x], &b = world_.positions[tri.y], &c = world_.positions[tri.z];
    float w = 1.0f - hit.u - hit.v;
    SurfacePoint sp;
    sp.position = w * a + hit.u * b + hit.v * c;
    sp.geometricNormal = glm::normalize(glm::cross(b - a, c - a));
    sp.shadingNormal = sp.geometricNormal;
    if (!world_.normals.empty()) {
        glm::vec3 n = w * world_.normals[tri.x] + hit.u * world_.normals[tri.y] + hit.v * world_.normals[tri.z];
        if (glm::dot(n, n) > 0.0f) sp.shadingNormal = glm::normalize(n);
    }
    if (!world_.uvs.empty()) sp.uv = w * world_.uvs[tri.x] + hit.u * world_.uvs[tri.y] + hit.v * world_.uvs[tri.z];
    if (!world_.colors.empty())
        sp.vertexColor = w * world_.colors[tri.x] + hit.u * world_.colors[tri.y] + hit.v * world_.colors[tri.z];
    sp.material = world_.faceMaterial.empty() ? 0 : world_.faceMaterial[hit.primId];
    sp.instance = instanceOf(hit.primId);
    return sp;
}

} // namespace wideray
