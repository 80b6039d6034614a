#pragma once
// Ray sets and the brute-force oracle shared by the traversal and kernel tests.
#include <random>
#include <vector>

#include "core/bounds.h"
#include "core/mesh.h"
#include "core/ray.h"
#include "kernels/hit_order.h"
#include "kernels/watertight.h"

namespace wideray::testing {

inline Bounds3f meshBounds(const TriangleMesh& mesh) {
    Bounds3f b;
    for (const glm::vec3& p : mesh.positions) b.grow(p);
    return b;
}

/// Rays from anywhere in the (enlarged) bounds: half in a uniform direction, the other half aimed at a
/// random point of a random triangle, so that most of them hit; with `aimedOnly` all are aimed.
inline std::vector<Ray> randomRays(const TriangleMesh& mesh, size_t count, uint32_t seed, bool aimedOnly = false) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    Bounds3f b = meshBounds(mesh);
    glm::vec3 lo = b.lower - 0.25f * b.extent(), size = 1.5f * b.extent();
    std::vector<Ray> rays(count);
    for (size_t i = 0; i < count; ++i) {
        glm::vec3 o = lo + glm::vec3(unit(rng), unit(rng), unit(rng)) * size;
        glm::vec3 d;
        if (!aimedOnly && i % 2 == 0) {
            float z = 1.0f - 2.0f * unit(rng), phi = 6.2831853f * unit(rng), r = std::sqrt(std::max(0.0f, 1 - z * z));
            d = {r * std::cos(phi), r * std::sin(phi), z};
        } else {
            const glm::uvec3& t = mesh.triangles[rng() % mesh.triangles.size()];
            float u = unit(rng), v = unit(rng);
            if (u + v > 1.0f) { u = 1.0f - u; v = 1.0f - v; }
            glm::vec3 target = mesh.positions[t.x] + u * (mesh.positions[t.y] - mesh.positions[t.x]) +
                               v * (mesh.positions[t.z] - mesh.positions[t.x]);
            d = glm::normalize(target - o);
            if (!(glm::dot(d, d) > 0.5f)) d = {0, 0, 1};
        }
        rays[i] = {o.x, o.y, o.z, d.x, d.y, d.z, 0.0f, std::numeric_limits<float>::infinity()};
    }
    return rays;
}

/// The closest hit by testing every triangle, with the same arithmetic and tie rule as the kernels.
inline Hit bruteForceHit(const TriangleMesh& mesh, const Ray& ray) {
    Hit hit;
    if (!isValidRay(ray)) return hit;
    hit.t = ray.tfar;
    auto woop = makeWatertightRay<float, int32_t>(ray.ox, ray.oy, ray.oz, ray.dx, ray.dy, ray.dz);
    for (uint32_t i = 0; i < mesh.triangles.size(); ++i) {
        const glm::uvec3& tri = mesh.triangles[i];
        const glm::vec3 &a = mesh.positions[tri.x], &b = mesh.positions[tri.y], &c = mesh.positions[tri.z];
        float t = 0, u = 0, v = 0;
        if (intersectWatertight(woop, true, a.x, a.y, a.z, b.x, b.y, b.z, c.x, c.y, c.z, ray.tnear, hit.t, t, u, v) &&
            isCloser(t, 0, i, hit))
            hit = {t, u, v, i, 0};
    }
    return hit.valid() ? hit : Hit{};
}

} // namespace wideray::testing
