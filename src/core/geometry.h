#pragma once
// The geometry interface: every kind of primitive a scene holds (triangle meshes, spheres, analytic
// primitives, CSG, instances) says how it is bounded and shaded. Triangle meshes hand their
// triangles to the acceleration structures, which store them in their own layouts; two-level
// instances hand them their meshes and placements; every other geometry is user geometry and
// intersects rays itself.
#include <cstdint>

#include <glm/glm.hpp>

#include "core/bounds.h"
#include "core/mesh.h"
#include "core/ray.h"

namespace wideray {

struct SurfacePoint {
    glm::vec3 position;
    glm::vec3 geometricNormal;  ///< unit length, facing whichever side the geometry defines as outside
    glm::vec3 shadingNormal;
    glm::vec2 uv{0.0f};
    uint32_t material = 0;
    uint32_t instance = kInvalidId;  ///< the scene instance the primitive belongs to, where it has one
    glm::vec3 vertexColor{1.0f};     ///< the mesh's per-vertex color here, which tints its material; white without one
};

class UserGeometry;
class InstanceGeometry;

class Geometry {
public:
    virtual ~Geometry() = default;
    virtual uint32_t primitiveCount() const = 0;
    virtual Bounds3f primitiveBounds(uint32_t primId) const = 0;
    /// The box around every primitive.
    virtual Bounds3f bounds() const = 0;
    virtual SurfacePoint surface(const Ray& ray, const Hit& hit) const = 0;

    /// The world-space triangles of a triangle mesh; null for user geometry.
    virtual const TriangleMesh* triangles() const { return nullptr; }
    /// This geometry as user geometry; null for triangle meshes.
    virtual const UserGeometry* user() const { return nullptr; }
    /// This geometry as two-level instances of meshes (geometry/instance_geometry.h); null otherwise.
    virtual const InstanceGeometry* instances() const { return nullptr; }
};

/// Geometry whose rays the kernels hand to the geometry itself, one primitive at a time.
class UserGeometry : public Geometry {
public:
    /// Returns true and writes t, u, v when the ray hits the primitive with tnear <= t <= tfar.
    virtual bool intersect(const Ray& ray, uint32_t primId, float tfar, float& t, float& u, float& v) const = 0;
    const UserGeometry* user() const final { return this; }
    Bounds3f bounds() const override;
};

} // namespace wideray
