#pragma once
// Tracing a scene through any backend and structure, for the tests that compare them all.
#include <memory>
#include <string>
#include <vector>

#include "backends/backend_registry.h"
#include "geometry/scene_geometry.h"

namespace wideray::testing {

/// The closest hits of `rays` through `backend`'s structure (`accel`: an --accel name, or empty).
inline std::vector<Hit> traceThrough(const std::shared_ptr<const SceneGeometry>& geometry, const std::string& backend,
                                     const std::string& accel, const std::vector<Ray>& rays) {
    StructureOptions options;
    options.accel = accel;
    std::vector<Hit> hits(rays.size());
    findBackend(backend).build(geometry, options)->tracer({})->intersect(rays, hits, Coherence::Incoherent);
    return hits;
}

/// nx * ny rays from `eye` through a grid of points from `lower` to `upper` on the plane z = 0.
inline std::vector<Ray> rayFan(const glm::vec3& eye, const glm::vec2& lower, const glm::vec2& upper, int nx, int ny) {
    std::vector<Ray> rays;
    for (int j = 0; j < ny; ++j)
        for (int i = 0; i < nx; ++i) {
            const glm::vec3 target(lower.x + (upper.x - lower.x) * float(i) / float(nx - 1),
                                   lower.y + (upper.y - lower.y) * float(j) / float(ny - 1), 0.0f);
            const glm::vec3 d = glm::normalize(target - eye);
            rays.push_back({eye.x, eye.y, eye.z, d.x, d.y, d.z});
        }
    return rays;
}

} // namespace wideray::testing
