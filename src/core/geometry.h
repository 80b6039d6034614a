#pragma once
// The geometry interface: how primitives other than the BVH's triangle blocks (spheres now; analytic
// primitives and CSG later) are bounded, intersected and shaded, without special cases in the kernels.
#include <cstdint>

#include <glm/glm.hpp>

#include "core/bounds.h"
#include "core/ray.h"

namespace wideray {

struct SurfacePoint {
    glm::vec3 position;
    glm::vec3 geometricNormal;  ///< unit length, facing whichever side the geometry defines as outside
    glm::vec3 shadingNormal;
    glm::vec2 uv{0.0f};
    uint32_t material = 0;
};

class Geometry {
public:
    virtual ~Geometry() = default;
    virtual uint32_t primitiveCount() const = 0;
    virtual Bounds3f primitiveBounds(uint32_t primId) const = 0;
    /// Returns true and writes t, u, v when the ray hits the primitive with tnear <= t <= tfar.
    virtual bool intersect(const Ray& ray, uint32_t primId, float tfar, float& t, float& u, float& v) const = 0;
    virtual SurfacePoint surface(const Ray& ray, const Hit& hit) const = 0;
};

} // namespace wideray
