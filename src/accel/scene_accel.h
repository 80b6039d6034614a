#pragma once
// Our acceleration structure of a scene: one N-wide BVH over all its primitives. Triangles sit in
// leaves of blocks laid out for SIMD intersection, user geometry (spheres) in leaves of primitive
// references; the two are built as subtrees and joined under one root.
#include <memory>
#include <vector>

#include "accel/bvh_binary.h"
#include "accel/bvh_view.h"
#include "geometry/scene_geometry.h"

namespace wideray {

struct BuildTimings {
    double binarySeconds = 0;
    double collapseSeconds = 0;
    double totalSeconds() const { return binarySeconds + collapseSeconds; }
};

template <int N>
class SceneAccel {
public:
    /// Built over every triangle mesh and every user geometry of `geometry`, which it keeps alive.
    explicit SceneAccel(std::shared_ptr<const SceneGeometry> geometry, const BvhBuildConfig& config = defaultConfig());

    static BvhBuildConfig defaultConfig() {
        BvhBuildConfig c;
        c.blockSize = kBlockSize;
        return c;
    }

    SceneView<N> view() const;
    const WideBvh<N>& bvh() const { return bvh_; }
    const TriangleBlocks& blocks() const { return blocks_; }
    const SceneGeometry& geometry() const { return *geometry_; }
    const BuildTimings& timings() const { return timings_; }
    /// Triangles in leaf blocks: the triangle count, more where spatial splits put one in several leaves.
    size_t triangleReferences() const;
    size_t bytes() const;

private:
    WideBvh<N> buildTriangles(const TriangleMesh& mesh, const BvhBuildConfig& config);
    /// At high quality, the cheaper (by SAH) of the builds with and without spatial splits.
    WideBvh<N> buildTrianglesAtBest(const TriangleMesh& mesh, const BvhBuildConfig& config);
    WideBvh<N> buildUser(const BvhBuildConfig& config);

    WideBvh<N> bvh_;
    TriangleBlocks blocks_;
    std::vector<PrimRef> prims_;
    std::shared_ptr<const SceneGeometry> geometry_;
    std::vector<const UserGeometry*> userGeometries_;  ///< indexed by geomId; null for triangle meshes
    BuildTimings timings_;
};

/// One build reference per triangle of the mesh, the builder's input.
std::vector<BuildRef> triangleRefs(const TriangleMesh& mesh);

} // namespace wideray
