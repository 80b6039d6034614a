#pragma once
// A scene's primitives one by one, as the course's structures (kd-tree, grids, binary and skip BVHs)
// list them in their leaves and cells: triangles first (item = primId of geomId 0), then every user
// primitive; with each item's box for the builders.
#include <vector>

#include "accel/course_views.h"
#include "accel/triangle_splitter.h"
#include "core/bounds.h"
#include "geometry/scene_geometry.h"

namespace wideray {

class PrimitiveTable {
public:
    explicit PrimitiveTable(const SceneGeometry& geometry);

    uint32_t size() const { return uint32_t(boxes_.size()); }
    bool isTriangle(uint32_t item) const { return item < triangles_.size(); }
    const Bounds3f& box(uint32_t item) const { return boxes_[item]; }
    /// The box around every item (empty without any).
    const Bounds3f& bounds() const { return bounds_; }
    /// A triangle item's vertices, for clipping.
    SplitTriangle triangle(uint32_t item) const;
    const TriangleVertices& vertices(uint32_t item) const { return triangles_[item]; }

    PrimitiveView view() const;
    size_t bytes() const;

private:
    std::vector<TriangleVertices> triangles_;
    std::vector<PrimRef> users_;
    std::vector<const UserGeometry*> geometries_;
    std::vector<Bounds3f> boxes_;
    Bounds3f bounds_;
};

} // namespace wideray
