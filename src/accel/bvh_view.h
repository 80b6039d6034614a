#pragma once
// Plain-pointer views of the acceleration structures: what the kernels receive, so that no standard
// container crosses into translation units compiled for another ISA.
#include <cstdint>

#include "accel/triangle_block.h"
#include "accel/wide_bvh.h"
#include "core/ray.h"

namespace wideray {

class UserGeometry;
template <int N>
struct SceneView;

/// A two-level instance as the kernels see it: the ray is taken into the object space of its mesh by
/// objectFromWorld (row-major 3x4, in double) and traced through the mesh's own BVH.
struct InstanceRef {
    double objectFromWorld[12];
    uint32_t mesh;       ///< index into InstanceTable's mesh views
    uint32_t firstPrim;  ///< the primId of its mesh's first triangle (geometry/instance_geometry.h)
    uint32_t motion = kInvalidId;  ///< a moving instance's index into InstanceTable::motions
};

/// A moving instance's world-from-object transforms (row-major 3x4) at times 0 and 1, interpolated
/// entry by entry for the ray's time and inverted per ray.
struct InstanceMotion {
    double worldFromObject[2][12];
};

/// The instances of a scene's BVH: its user leaves' primitives of geometry geomId are instances.
struct InstanceTable {
    uint32_t geomId = kInvalidId;
    const InstanceRef* instances = nullptr;
    const InstanceMotion* motions = nullptr;
    const SceneView<4>* meshes4 = nullptr;  ///< one BVH per instanced mesh, of the scene BVH's width
    const SceneView<8>* meshes8 = nullptr;
    const SceneView<16>* meshes16 = nullptr;

    /// The member holding the mesh views of width N (assignable on a non-const table).
    template <int N>
    auto& meshes() { return meshesOf<N>(*this); }
    template <int N>
    const SceneView<N>* meshes() const { return meshesOf<N>(*this); }

private:
    template <int N, class Table>
    static auto& meshesOf(Table& table) {
        static_assert(N == 4 || N == 8 || N == 16);
        if constexpr (N == 4) return table.meshes4;
        else if constexpr (N == 8) return table.meshes8;
        else return table.meshes16;
    }
};

/// A user primitive: primitive primId of geometry geomId.
struct PrimRef {
    uint32_t geomId;
    uint32_t primId;
};

/// The items the leaves of a scene's BVH point to: triangle blocks (geomId 0), and user primitives
/// (and instances) for leaves with NodeRef::kUserFlag.
struct SceneLeaves {
    const TriangleBlock<kBlockSize>* blocks = nullptr;
    const PrimRef* prims = nullptr;
    const UserGeometry* const* geometries = nullptr;  ///< indexed by geomId; null for triangles and instances
    const InstanceTable* instances = nullptr;         ///< null without two-level instances
};

/// One N-wide BVH over all of a scene's primitives.
template <int N>
struct SceneView {
    const WideNode<N>* nodes = nullptr;
    NodeRef root = NodeRef::empty();
    SceneLeaves leaves;
    Bounds3f bounds;  ///< of the whole tree
};

} // namespace wideray
