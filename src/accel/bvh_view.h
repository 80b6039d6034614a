#pragma once
// Plain-pointer views of the acceleration structures: what the kernels receive, so that no standard
// container crosses into translation units compiled for another ISA.
#include <cstdint>

#include "accel/triangle_block.h"
#include "accel/wide_bvh.h"

namespace wideray {

class UserGeometry;

template <int N>
struct TriangleBvhView {
    const WideNode<N>* nodes = nullptr;
    NodeRef root = NodeRef::empty();
    const TriangleBlock<kBlockSize>* blocks = nullptr;
};

/// A user primitive: primitive primId of geometry geomId (geomId >= 1; 0 is the triangles).
struct PrimRef {
    uint32_t geomId;
    uint32_t primId;
};

template <int N>
struct UserBvhView {
    const WideNode<N>* nodes = nullptr;
    NodeRef root = NodeRef::empty();
    const PrimRef* prims = nullptr;
    const UserGeometry* const* geometries = nullptr;  ///< indexed by geomId
};

template <int N>
struct SceneView {
    TriangleBvhView<N> triangles;
    UserBvhView<N> user;
};

} // namespace wideray
