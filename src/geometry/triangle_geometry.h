#pragma once
// The instanced triangle meshes of a scene as one geometry: each instance's triangles transformed to
// world space, in instance order, so that a primId names one triangle of one instance. The current
// acceleration structures place them all in one tree; a two-level structure would keep the
// instances apart (docs/architecture.md).
#include <vector>

#include "core/geometry.h"
#include "core/scene.h"

namespace wideray {

class TriangleGeometry final : public Geometry {
public:
    /// The scene's instances of the meshes not marked in `twoLevel` (empty: all), flattened.
    explicit TriangleGeometry(const SceneDescription& scene, const std::vector<bool>& twoLevel = {});
    /// One mesh placed once, as it is.
    explicit TriangleGeometry(TriangleMesh mesh);

    uint32_t primitiveCount() const override { return uint32_t(world_.triangles.size()); }
    Bounds3f primitiveBounds(uint32_t primId) const override;
    /// The box around every vertex.
    Bounds3f bounds() const override;
    SurfacePoint surface(const Ray& ray, const Hit& hit) const override;
    const TriangleMesh* triangles() const override { return &world_; }

    /// The scene instance a triangle belongs to.
    uint32_t instanceOf(uint32_t primId) const { return instanceIds_[slotOf(primId)]; }
    /// The primId of the first triangle of that instance.
    uint32_t instanceFirstPrim(uint32_t primId) const { return instanceFirst_[slotOf(primId)]; }

private:
    /// The last instance flattened that starts at or before primId.
    size_t slotOf(uint32_t primId) const;

    TriangleMesh world_;
    std::vector<uint32_t> instanceFirst_;  ///< the first primId of each instance flattened
    std::vector<uint32_t> instanceIds_;    ///< the scene instance of each
};

/// The instanced triangles in world space, in one mesh (of the meshes not marked in `twoLevel`;
/// empty: all); faceMaterial indexes scene.materials.
TriangleMesh flattenTriangles(const SceneDescription& scene, const std::vector<bool>& twoLevel = {});

} // namespace wideray
