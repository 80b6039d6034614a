#pragma once
// The acceleration structures of a scene: an N-wide BVH over its triangles, laid out in blocks for
// SIMD intersection, and one over its user geometry (spheres).
#include <memory>
#include <vector>

#include "accel/bvh_binary.h"
#include "accel/bvh_view.h"
#include "core/geometry.h"
#include "core/mesh.h"

namespace wideray {

struct BuildTimings {
    double binarySeconds = 0;
    double collapseSeconds = 0;
    double totalSeconds() const { return binarySeconds + collapseSeconds; }
};

template <int N>
class SceneAccel {
public:
    /// geometries[0] must be null (geomId 0 is the triangle mesh); the others are user geometry.
    SceneAccel(const TriangleMesh& triangles, std::vector<std::unique_ptr<Geometry>> geometries,
               const BvhBuildConfig& config = defaultConfig());

    static BvhBuildConfig defaultConfig() {
        BvhBuildConfig c;
        c.blockSize = kBlockSize;
        return c;
    }

    SceneView<N> view() const;
    const WideBvh<N>& triangleBvh() const { return triangleBvh_; }
    const std::vector<TriangleBlock<kBlockSize>>& blocks() const { return blocks_; }
    const Geometry& geometry(uint32_t geomId) const { return *geometries_[geomId]; }
    const BuildTimings& timings() const { return timings_; }
    size_t bytes() const;

private:
    void buildTriangles(const TriangleMesh& mesh, const BvhBuildConfig& config);
    void buildUser(const BvhBuildConfig& config);

    WideBvh<N> triangleBvh_;
    std::vector<TriangleBlock<kBlockSize>> blocks_;
    WideBvh<N> userBvh_;
    std::vector<PrimRef> prims_;
    std::vector<std::unique_ptr<Geometry>> geometries_;
    std::vector<const Geometry*> geometryPointers_;
    BuildTimings timings_;
};

/// Bounds and centers of a mesh's triangles, the builder's input.
void triangleBounds(const TriangleMesh& mesh, std::vector<Bounds3f>& bounds, std::vector<glm::vec3>& centers);

} // namespace wideray
