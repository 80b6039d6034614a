#pragma once
// Binary BVH built with the binned surface area heuristic (Wald 2007, "On fast construction of
// SAH-based bounding volume hierarchies"). It is the input of the wide collapse, not a tracing layout.
#include <cstdint>
#include <span>
#include <vector>

#include "core/bounds.h"

namespace wideray {

struct BinaryNode {
    Bounds3f bounds;
    uint32_t first = 0;  ///< leaf: first entry of primIndices; inner: left child (right is first + 1)
    uint32_t count = 0;  ///< primitives in a leaf; 0 for an inner node

    bool isLeaf() const { return count > 0; }
};

struct BinaryBvh {
    std::vector<BinaryNode> nodes;  ///< nodes[0] is the root
    std::vector<uint32_t> primIndices;
};

enum class SplitMethod { Sah, Median };

/// How the binary tree becomes a wide one: the SAH-optimal collapse (dynamic programming), or greedily
/// opening the largest child until a node has N.
enum class CollapseMethod { Sah, Greedy };

struct BvhBuildConfig {
    SplitMethod split = SplitMethod::Sah;
    CollapseMethod collapse = CollapseMethod::Sah;
    int binCount = 32;
    int maxLeafSize = 8;
    /// Leaves are intersected in blocks of this many primitives, so the SAH charges whole blocks.
    int blockSize = 1;
    float traversalCost = 1.0f;
    float intersectionCost = 1.0f;
};

/// The deepest a build goes; past kMedianDepth it splits at the object median, which bounds the depth.
constexpr int kMaxBvhDepth = 64;

/// Builds over primitive boxes and their centers (both of the same length, at least one). Parallel
/// with oneTBB; the tree's shape does not depend on the thread count.
BinaryBvh buildBinaryBvh(std::span<const Bounds3f> primBounds, std::span<const glm::vec3> centers,
                         const BvhBuildConfig& config);

} // namespace wideray
