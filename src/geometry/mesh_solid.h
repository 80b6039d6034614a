#pragma once
// A closed triangle mesh as a solid for CSG: its triangles in world space, a binary BVH over them, and
// every crossing of a ray's line with its surface. Each triangle the line meets counts +1 where the
// line passes against its outward (counter-clockwise) normal and -1 where along it, and the line is
// inside while the count is positive; a line through an edge or a vertex meets exactly one of the
// triangles there (watertight test in double precision, ties broken by simulation of simplicity).
#include <vector>

#include "core/bounds.h"
#include "core/geometry.h"
#include "core/scene.h"
#include "geometry/solid_crossing.h"
#include "geometry/triangle_geometry.h"

namespace wideray {

class MeshSolid {
public:
    /// The instance's mesh placed in world space (meshes[instance.mesh] must be closed).
    MeshSolid(const std::vector<TriangleMesh>& meshes, const MeshInstance& instance);

    Bounds3f bounds() const { return geometry_.bounds(); }
    /// Appends the line's crossings of the solid in increasing t (primId: the triangle; u, v: the
    /// weights of its second and third vertex).
    void crossings(const Ray& ray, SolidCrossings& out) const;
    /// The surface at a crossing given as the hit (t, primId, u, v).
    SurfacePoint surface(const Ray& ray, const Hit& hit) const { return geometry_.surface(ray, hit); }

private:
    struct Node {
        Bounds3f box;
        uint32_t first, count;  ///< a leaf's triangles in order_, or count 0 and first the right child (left is next)
    };
    uint32_t build(uint32_t first, uint32_t count, std::vector<glm::vec3>& centers);

    TriangleGeometry geometry_;
    std::vector<Node> nodes_;
    std::vector<uint32_t> order_;  ///< triangle indices, leaf by leaf
};

} // namespace wideray
