#pragma once
// Plain-pointer views of the course's structures (binary and skip-pointer BVHs, kd-tree, uniform,
// hierarchical and recursive grids): what their kernels receive, compiled once per ISA like the wide
// BVH's (accel/bvh_view.h). Unlike the wide BVH, their leaves and cells list primitives one by one,
// as indices ("items") into one table of the scene's primitives.
#include <cstdint>

#include "accel/bvh_view.h"

namespace wideray {

/// A triangle's vertices, in the order the reference's blocks hold them (so the same test, the same t).
struct TriangleVertices {
    float v0x, v0y, v0z, v1x, v1y, v1z, v2x, v2y, v2z;
};

/// Every primitive of a scene by item index: items below triangleCount are triangle `item` of geomId
/// 0, the rest the user primitives users[item - triangleCount].
struct PrimitiveView {
    const TriangleVertices* triangles = nullptr;
    uint32_t triangleCount = 0;
    const PrimRef* users = nullptr;
    const UserGeometry* const* geometries = nullptr;  ///< indexed by geomId
};

/// A box as its six planes, indexed like WideNode::planes: 2 * axis + (upper ? 1 : 0).
struct BoxPlanes {
    float plane[6];
};

/// A node of the binary BVH: inner nodes' children are nodes `first` and `first + 1`; leaves list
/// `count` items from items[first].
struct Bvh2Node {
    BoxPlanes box;
    uint32_t first;
    uint32_t count;  ///< 0 for inner nodes
};

struct Bvh2View {
    const Bvh2Node* nodes = nullptr;  ///< nodes[0] is the root; null for an empty scene
    const uint32_t* items = nullptr;
    PrimitiveView prims;
};

/// A node of the skip-pointer BVH, stored in depth-first order: a node's first child follows it, and
/// `skip` is the node after its subtree (nodeCount at the end), where a ray goes when it misses the
/// box or leaves a leaf.
struct SkipNode {
    BoxPlanes box;
    uint32_t skip;
    uint32_t first;  ///< leaves: their first item
    uint32_t count;  ///< items of a leaf; 0 for inner nodes
};

struct SkipView {
    const SkipNode* nodes = nullptr;
    uint32_t nodeCount = 0;
    const uint32_t* items = nullptr;
    PrimitiveView prims;
};

/// A kd-tree node in 8 bytes: inner nodes split `axis` at `split`, their lower child follows them
/// and the upper one is node `payload`; leaves (axis 3) list `count` items from items[payload].
struct KdNode {
    static constexpr uint32_t kLeafAxis = 3;
    union {
        float split;
        uint32_t payload;
    };
    uint32_t bits;  ///< axis in the low 2 bits; inner: upper child index above them; leaves: count

    uint32_t axis() const { return bits & 3u; }
    bool isLeaf() const { return axis() == kLeafAxis; }
    uint32_t upperChild() const { return bits >> 2; }
    uint32_t count() const { return bits >> 2; }
    uint32_t firstItem() const { return payload; }
};
static_assert(sizeof(KdNode) == 8);

/// The deepest a kd-tree goes (its traversal stack's size).
constexpr int kMaxKdTreeDepth = 64;

struct KdTreeView {
    const KdNode* nodes = nullptr;  ///< null for an empty scene
    const uint32_t* items = nullptr;
    BoxPlanes bounds;               ///< the root's box
    PrimitiveView prims;
};

/// A cell of a grid: `count` items from items[first], or (kSubgridFlag) the finer grid number `first`.
struct GridCell {
    static constexpr uint32_t kSubgridFlag = 0x80000000u;
    uint32_t first;
    uint32_t count;

    bool isSubgrid() const { return count & kSubgridFlag; }
};

/// One grid of a (possibly nested) grid: res[a] cells along axis a over its box, cells from
/// cells[firstCell] in x-fastest order.
struct GridLevel {
    float lower[3], upper[3];
    float cellSize[3], invCellSize[3];
    int32_t res[3];
    uint32_t firstCell;
};

/// Uniform grids are one level; hierarchical and recursive grids nest finer grids in crowded cells.
struct GridView {
    const GridLevel* grids = nullptr;  ///< grids[0] is the top level; null for an empty scene
    const GridCell* cells = nullptr;
    const uint32_t* items = nullptr;
    PrimitiveView prims;
};

} // namespace wideray
