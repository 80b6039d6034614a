#include "geometry/scene_geometry.h"

#include "geometry/geometry_registry.h"
#include "geometry/triangle_geometry.h"

namespace wideray {

Bounds3f UserGeometry::bounds() const {
    Bounds3f b;
    for (uint32_t p = 0; p < primitiveCount(); ++p) b.grow(primitiveBounds(p));
    return b;
}

SceneGeometry::SceneGeometry(const SceneDescription& scene, Instancing instancing) {
    const std::vector<bool> twoLevel = twoLevelMeshes(scene, instancing);
    for (const GeometryKind& kind : geometryKinds())
        if (std::unique_ptr<Geometry> g = kind.make(scene, twoLevel)) geometries_.push_back(std::move(g));
}

SceneGeometry::SceneGeometry(TriangleMesh mesh) {
    geometries_.push_back(std::make_unique<TriangleGeometry>(std::move(mesh)));
}

Bounds3f SceneGeometry::bounds() const {
    Bounds3f b;
    for (const auto& g : geometries_) b.grow(g->bounds());
    return b;
}

uint64_t SceneGeometry::triangleCount() const {
    uint64_t n = 0;
    for (const auto& g : geometries_) {
        if (const TriangleMesh* t = g->triangles()) n += t->triangles.size();
        if (const InstanceGeometry* i = g->instances())
            for (const auto& mesh : i->meshes()) n += mesh->triangleCount();
    }
    return n;
}

uint64_t SceneGeometry::instancedTriangleCount() const {
    uint64_t n = 0;
    for (const auto& g : geometries_) {
        if (const TriangleMesh* t = g->triangles()) n += t->triangles.size();
        if (const InstanceGeometry* i = g->instances()) n += i->instancedTriangles();
    }
    return n;
}

const InstanceGeometry* SceneGeometry::instances() const {
    for (const auto& g : geometries_)
        if (const InstanceGeometry* i = g->instances()) return i;
    return nullptr;
}

} // namespace wideray
