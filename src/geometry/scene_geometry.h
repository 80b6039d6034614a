#pragma once
// The geometry of a scene, built once from the scene model: a list of geometries indexed by geomId,
// made by the factories of geometry_registry.h in their order. The renderer, every acceleration
// structure and every backend read the scene's primitives from here.
#include <memory>
#include <vector>

#include "core/geometry.h"
#include "core/scene.h"
#include "geometry/instance_geometry.h"

namespace wideray {

class SceneGeometry {
public:
    explicit SceneGeometry(const SceneDescription& scene, Instancing instancing = Instancing::Auto);
    /// A scene of one mesh and nothing else (tests, benchmarks).
    explicit SceneGeometry(TriangleMesh mesh);

    uint32_t size() const { return uint32_t(geometries_.size()); }
    const Geometry& operator[](uint32_t geomId) const { return *geometries_[geomId]; }

    /// The box around every geometry; empty when there is none.
    Bounds3f bounds() const;
    /// The triangles stored: of the triangle geometry and each instanced mesh once.
    uint64_t triangleCount() const;
    /// The triangles of the scene's instances, as many as the flattened form has.
    uint64_t instancedTriangleCount() const;
    /// The two-level instances; null when there are none.
    const InstanceGeometry* instances() const;
    SurfacePoint surface(const Ray& ray, const Hit& hit) const { return geometries_[hit.geomId]->surface(ray, hit); }

private:
    std::vector<std::unique_ptr<Geometry>> geometries_;
};

} // namespace wideray
