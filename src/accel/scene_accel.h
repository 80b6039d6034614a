#pragma once
// Our acceleration structure of a scene: one N-wide BVH over all its primitives. Triangles sit in
// leaves of blocks laid out for SIMD intersection, user geometry (spheres, analytic primitives, CSG)
// and two-level instances in leaves of primitive references; the two are built as subtrees and
// joined under one root. Each instanced mesh has a SceneAccel of its own, in object space.
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
    SceneAccel(const SceneAccel&) = delete;  // view() points into its own arrays
    SceneAccel& operator=(const SceneAccel&) = delete;

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
    /// All of it: the scene's tree, its leaves, the instanced meshes' structures and the instances.
    size_t bytes() const;
    /// About what the structure would take with its instances flattened: each instance a copy of its
    /// mesh's structure, without the top level.
    size_t flattenedBytes() const;
    /// The instanced meshes' structures, one per mesh; empty without two-level instances.
    const std::vector<std::unique_ptr<SceneAccel<N>>>& instancedMeshes() const { return meshAccels_; }

private:
    WideBvh<N> buildTriangles(const TriangleMesh& mesh, const BvhBuildConfig& config);
    /// At high quality, the cheaper (by SAH) of the builds with and without spatial splits.
    WideBvh<N> buildTrianglesAtBest(const TriangleMesh& mesh, const BvhBuildConfig& config);
    WideBvh<N> buildUser(const BvhBuildConfig& config);
    void buildInstances(uint32_t geomId, const InstanceGeometry& instances, const BvhBuildConfig& config);

    WideBvh<N> bvh_;
    TriangleBlocks blocks_;
    std::vector<PrimRef> prims_;
    std::shared_ptr<const SceneGeometry> geometry_;
    std::vector<const UserGeometry*> userGeometries_;  ///< indexed by geomId; null for triangle meshes
    std::vector<std::unique_ptr<SceneAccel<N>>> meshAccels_;
    std::vector<SceneView<N>> meshViews_;
    std::vector<InstanceRef> instanceRefs_;
    std::vector<InstanceMotion> instanceMotions_;
    InstanceTable instanceTable_;
    BuildTimings timings_;
};

/// One build reference per triangle of the mesh, the builder's input, with room reserved for `capacity`
/// (see buildRefCapacity).
BuildRefs triangleRefs(const TriangleMesh& mesh, size_t capacity = 0);

} // namespace wideray
