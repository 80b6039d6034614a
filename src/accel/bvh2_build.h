#pragma once
// The binary SAH BVH as a tracing layout (bvh2), and the same tree threaded in depth-first order with
// miss links (skip), both over a PrimitiveTable's items, one item per leaf slot.
#include <vector>

#include "accel/bvh_binary.h"
#include "accel/primitive_table.h"

namespace wideray {

struct Bvh2 {
    std::vector<Bvh2Node> nodes;  ///< empty for an empty scene
    std::vector<uint32_t> items;
    int depth = 0;
    size_t leaves = 0;
};

struct SkipTree {
    std::vector<SkipNode> nodes;
    std::vector<uint32_t> items;
};

/// Object splits, binned SAH (the wide BVH's builder at fast quality), leaves of up to 4 items.
Bvh2 buildBvh2(const PrimitiveTable& table);
/// The tree in depth-first order, each node's left child first.
SkipTree threadBvh2(const Bvh2& bvh);

BoxPlanes boxPlanes(const Bounds3f& b);

} // namespace wideray
