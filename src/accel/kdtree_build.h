#pragma once
// The SAH kd-tree of Wald and Havran (2006, "On building fast kd-trees for ray tracing, and on doing
// that in O(N log N)"): the candidate planes are the sides of each item's box clipped to the node
// ("perfect splits"), swept in an event list sorted once at the root and kept sorted by splitting it;
// items across a plane are clipped to either side, and cutting off empty space earns a bonus.
#include <cstddef>
#include <vector>

#include "accel/primitive_table.h"

namespace wideray {

struct KdTreeConfig {
    float traversalCost = 15.0f;    ///< K_T of the paper
    float intersectionCost = 20.0f; ///< K_I
    float emptyBonus = 0.8f;        ///< the cost's factor where a side is empty (lambda)
    /// 0: 8 + 1.3 log2 N (pbrt), at most kMaxKdTreeDepth.
    int maxDepth = 0;
};

struct KdTree {
    std::vector<KdNode> nodes;  ///< empty for an empty scene
    std::vector<uint32_t> items;
    Bounds3f bounds;
    int depth = 0;
    size_t leaves = 0, emptyLeaves = 0;
};

KdTree buildKdTree(const PrimitiveTable& table, const KdTreeConfig& config = {});

} // namespace wideray
