#include "io/mesh_generators.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>
#include <string>
#include <utility>

namespace wideray {

TriangleMesh makeCube() {
    TriangleMesh mesh;
    // Vertex i has x = bit 0, y = bit 1, z = bit 2 (0 -> -1, 1 -> +1).
    for (int i = 0; i < 8; ++i)
        mesh.positions.push_back({(i & 1) ? 1.0f : -1.0f, (i & 2) ? 1.0f : -1.0f, (i & 4) ? 1.0f : -1.0f});
    mesh.triangles = {
        {0, 4, 6}, {0, 6, 2},  // -x
        {1, 3, 7}, {1, 7, 5},  // +x
        {0, 1, 5}, {0, 5, 4},  // -y
        {2, 6, 7}, {2, 7, 3},  // +y
        {0, 2, 3}, {0, 3, 1},  // -z
        {4, 5, 7}, {4, 7, 6},  // +z
    };
    return mesh;
}

TriangleMesh makeQuad() {
    TriangleMesh mesh;
    mesh.positions = {{-1.0f, 0.0f, -1.0f}, {1.0f, 0.0f, -1.0f}, {1.0f, 0.0f, 1.0f}, {-1.0f, 0.0f, 1.0f}};
    mesh.uvs = {{0.0f, 0.0f}, {1.0f, 0.0f}, {1.0f, 1.0f}, {0.0f, 1.0f}};
    mesh.triangles = {{0, 2, 1}, {0, 3, 2}};
    return mesh;
}

TriangleMesh makeIcosphere(int subdivisions) {
    if (subdivisions < 0 || subdivisions > 10)
        throw std::invalid_argument("makeIcosphere: subdivisions must be in 0..10, got " + std::to_string(subdivisions));
    TriangleMesh mesh;
    const float t = (1.0f + std::sqrt(5.0f)) / 2.0f;
    mesh.positions = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0}, {0, -1, t}, {0, 1, t},
                      {0, -1, -t}, {0, 1, -t}, {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
    for (glm::vec3& p : mesh.positions) p = glm::normalize(p);
    mesh.triangles = {{0, 11, 5}, {0, 5, 1}, {0, 1, 7}, {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
                      {11, 10, 2}, {10, 7, 6}, {7, 1, 8}, {3, 9, 4}, {3, 4, 2}, {3, 2, 6}, {3, 6, 8},
                      {3, 8, 9}, {4, 9, 5}, {2, 4, 11}, {6, 2, 10}, {8, 6, 7}, {9, 8, 1}};

    for (int level = 0; level < subdivisions; ++level) {
        // Both triangles beside an edge must get the same midpoint vertex, or the sphere would crack.
        std::map<std::pair<uint32_t, uint32_t>, uint32_t> midpointOfEdge;
        auto midpoint = [&](uint32_t a, uint32_t b) {
            const std::pair<uint32_t, uint32_t> key = std::minmax(a, b);
            auto [it, inserted] = midpointOfEdge.try_emplace(key, uint32_t(mesh.positions.size()));
            if (inserted) mesh.positions.push_back(glm::normalize(mesh.positions[a] + mesh.positions[b]));
            return it->second;
        };
        std::vector<glm::uvec3> finer;
        finer.reserve(mesh.triangles.size() * 4);
        for (const glm::uvec3& tri : mesh.triangles) {
            const uint32_t ab = midpoint(tri.x, tri.y), bc = midpoint(tri.y, tri.z), ca = midpoint(tri.z, tri.x);
            finer.push_back({tri.x, ab, ca});
            finer.push_back({tri.y, bc, ab});
            finer.push_back({tri.z, ca, bc});
            finer.push_back({ab, bc, ca});
        }
        mesh.triangles = std::move(finer);
    }
    mesh.normals = mesh.positions;
    return mesh;
}

TriangleMesh makeTorus(float majorRadius, float minorRadius, int majorSegments, int minorSegments) {
    if (!(minorRadius > 0.0f && minorRadius < majorRadius))
        throw std::invalid_argument("makeTorus: need 0 < minorRadius < majorRadius");
    if (majorSegments < 3 || minorSegments < 3)
        throw std::invalid_argument("makeTorus: need at least 3 segments each way");
    TriangleMesh mesh;
    const float twoPi = 6.28318530717958647692f;
    for (int i = 0; i < majorSegments; ++i) {
        const float u = twoPi * float(i) / float(majorSegments);
        const glm::vec3 outward{std::cos(u), 0.0f, std::sin(u)};
        for (int j = 0; j < minorSegments; ++j) {
            const float v = twoPi * float(j) / float(minorSegments);
            const glm::vec3 normal = std::cos(v) * outward + glm::vec3(0.0f, std::sin(v), 0.0f);
            mesh.positions.push_back(majorRadius * outward + minorRadius * normal);
            mesh.normals.push_back(normal);
        }
    }
    // The last ring and the last segment of each ring wrap around to index 0 instead of repeating it.
    auto vertex = [&](int i, int j) {
        return uint32_t((i % majorSegments) * minorSegments + (j % minorSegments));
    };
    for (int i = 0; i < majorSegments; ++i) {
        for (int j = 0; j < minorSegments; ++j) {
            const uint32_t a = vertex(i, j), b = vertex(i + 1, j), c = vertex(i + 1, j + 1), d = vertex(i, j + 1);
            mesh.triangles.push_back({a, d, c});
            mesh.triangles.push_back({a, c, b});
        }
    }
    return mesh;
}

} // namespace wideray
