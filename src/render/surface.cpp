#include "render/surface.h"

namespace wideray {

SurfacePoint surfaceAt(const TriangleMesh& world, const Tracer& tracer, const Ray& ray, const Hit& hit) {
    if (hit.geomId != 0) return tracer.geometry(hit.geomId).surface(ray, hit);
    const glm::uvec3& tri = world.triangles[hit.primId];
    const glm::vec3 &a = world.positions[tri.x], &b = world.positions[tri.y], &c = world.positions[tri.z];
    float w = 1.0f - hit.u - hit.v;
    SurfacePoint sp;
    sp.position = w * a + hit.u * b + hit.v * c;
    sp.geometricNormal = glm::normalize(glm::cross(b - a, c - a));
    sp.shadingNormal = sp.geometricNormal;
    if (!world.normals.empty()) {
        glm::vec3 n = w * world.normals[tri.x] + hit.u * world.normals[tri.y] + hit.v * world.normals[tri.z];
        if (glm::dot(n, n) > 0.0f) sp.shadingNormal = glm::normalize(n);
    }
    if (!world.uvs.empty()) sp.uv = w * world.uvs[tri.x] + hit.u * world.uvs[tri.y] + hit.v * world.uvs[tri.z];
    sp.material = world.faceMaterial.empty() ? 0 : world.faceMaterial[hit.primId];
    return sp;
}

} // namespace wideray
