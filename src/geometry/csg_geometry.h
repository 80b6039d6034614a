#pragma once
// Constructive solid geometry (core/scene.h, CsgObject) as user geometry. A ray's line is crossed
// with every solid of the tree whose box it passes (analytic solids through AnalyticGeometry, closed
// meshes through MeshSolid), the crossings are merged in t, and the tree's set operations are
// evaluated after each group of crossings at one t: the first change between outside and inside in
// [tnear, tfar] is the hit. Its surface is the crossed solid's, with that solid's material and the
// normal turned to face out of the CSG object (a difference's carved faces point into the hole).
#include <memory>
#include <vector>

#include "core/geometry.h"
#include "core/scene.h"
#include "geometry/analytic_geometry.h"
#include "geometry/mesh_solid.h"
#include "geometry/solid_crossing.h"

namespace wideray {

class CsgGeometry final : public UserGeometry {
public:
    CsgGeometry(const std::vector<CsgObject>& objects, const std::vector<TriangleMesh>& meshes);

    uint32_t primitiveCount() const override { return uint32_t(trees_.size()); }
    Bounds3f primitiveBounds(uint32_t primId) const override { return trees_[primId].bounds; }
    bool intersect(const Ray& ray, uint32_t primId, float tfar, float& t, float& u, float& v) const override;
    SurfacePoint surface(const Ray& ray, const Hit& hit) const override;

private:
    struct Leaf {
        bool mesh;       ///< a MeshSolid, else a solid of analytics_
        uint32_t solid;  ///< index into meshes_ or analytics_
        Bounds3f bounds;
    };
    struct Tree {
        std::vector<CsgNode> nodes;  ///< leaf nodes' `solid` index leaves_ (from firstLeaf)
        uint32_t firstLeaf = 0, leafCount = 0;
        Bounds3f bounds;
    };

    /// Whether the tree's node holds a point where `inside` says which of the tree's leaves hold it.
    static bool contains(const Tree& tree, uint32_t node, const std::vector<uint8_t>& inside);
    Bounds3f nodeBounds(const Tree& tree, uint32_t node) const;
    struct ObjectCrossing {
        SolidCrossing crossing;  ///< of the solid crossed (its leaf, whether the line enters that solid)
        bool entersObject;       ///< whether the line enters the CSG object there
    };
    /// The first crossing of the object's boundary in [tnear, tfar].
    bool firstCrossing(const Tree& tree, const Ray& ray, double tnear, double tfar, ObjectCrossing& hit) const;

    std::unique_ptr<AnalyticGeometry> analytics_;
    std::vector<MeshSolid> meshes_;
    std::vector<Leaf> leaves_;
    std::vector<Tree> trees_;
};

} // namespace wideray
