#pragma once
// Shape and cost of a BVH: what `wideray info` prints and what the tests compare.
#include <cstddef>

#include "accel/bvh_binary.h"
#include "accel/wide_bvh.h"

namespace wideray {

struct BvhStats {
    size_t innerNodes = 0;
    size_t children = 0;   ///< non-empty child slots of the inner nodes (wide BVHs)
    size_t leaves = 0;
    size_t leafItems = 0;  ///< triangle blocks or primitive references
    int depth = 0;         ///< levels of inner nodes on the longest path
    /// SAH cost: sum over inner nodes of traversalCost * area / rootArea plus sum over leaves of
    /// intersectionCost * items * area / rootArea.
    double sahCost = 0;

    /// Children per inner node, out of N for an N-wide BVH.
    double childrenPerNode() const { return innerNodes ? double(children) / double(innerNodes) : 0.0; }
};

BvhStats binaryBvhStats(const BinaryBvh& bvh, const BvhBuildConfig& config);

template <int N>
BvhStats wideBvhStats(const WideBvh<N>& bvh, const BvhBuildConfig& config);

} // namespace wideray
