#pragma once
// Plain-pointer views of the acceleration structures: what the kernels receive, so that no standard
// container crosses into translation units compiled for another ISA.
#include <cstdint>

#include "accel/triangle_block.h"
#include "accel/wide_bvh.h"

namespace wideray {

class UserGeometry;

/// A user primitive: primitive primId of geometry geomId.
struct PrimRef {
    uint32_t geomId;
    uint32_t primId;
};

/// The items the leaves of a scene's BVH point to: triangle blocks (geomId 0), and user primitives
/// for leaves with NodeRef::kUserFlag.
struct SceneLeaves {
    const TriangleBlock<kBlockSize>* blocks = nullptr;
    const PrimRef* prims = nullptr;
    const UserGeometry* const* geometries = nullptr;  ///< indexed by geomId
};

/// One N-wide BVH over all of a scene's primitives.
template <int N>
struct SceneView {
    const WideNode<N>* nodes = nullptr;
    NodeRef root = NodeRef::empty();
    SceneLeaves leaves;
};

} // namespace wideray
