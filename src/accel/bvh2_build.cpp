#include "accel/bvh2_build.h"

#include <algorithm>

namespace wideray {

BoxPlanes boxPlanes(const Bounds3f& b) {
    return {{b.lower.x, b.upper.x, b.lower.y, b.upper.y, b.lower.z, b.upper.z}};
}

Bvh2 buildBvh2(const PrimitiveTable& table) {
    Bvh2 out;
    if (table.size() == 0) return out;
    BuildRefs refs(table.size());
    for (uint32_t i = 0; i < table.size(); ++i) refs[i] = makeBuildRef(table.box(i), i);
    BvhBuildConfig config;
    config.maxLeafSize = 4;
    const BinaryBvh binary = buildBinaryBvh(std::move(refs), config);
    out.items.assign(binary.primIndices.begin(), binary.primIndices.end());
    out.nodes.reserve(binary.nodes.size());
    for (const BinaryNode& n : binary.nodes) {
        out.nodes.push_back({boxPlanes(n.bounds), n.first, n.count});
        out.leaves += n.isLeaf() ? 1 : 0;
    }
    // Depth by one pass from the root: children always follow their parent in the node array.
    std::vector<int> depth(out.nodes.size(), 1);
    for (size_t i = 0; i < out.nodes.size(); ++i) {
        out.depth = std::max(out.depth, depth[i]);
        if (out.nodes[i].count == 0) depth[out.nodes[i].first] = depth[out.nodes[i].first + 1] = depth[i] + 1;
    }
    return out;
}

SkipTree threadBvh2(const Bvh2& bvh) {
    SkipTree out;
    out.items = bvh.items;
    if (bvh.nodes.empty()) return out;
    out.nodes.reserve(bvh.nodes.size());
    // Pre-order with an explicit stack; a node's skip link is set once its subtree is written.
    struct Pending {
        uint32_t node;
        uint32_t written;  ///< its index in the output, for the skip link (UINT32_MAX: not yet written)
    };
    std::vector<Pending> stack{{0, UINT32_MAX}};
    while (!stack.empty()) {
        Pending& p = stack.back();
        if (p.written != UINT32_MAX) {
            out.nodes[p.written].skip = uint32_t(out.nodes.size());
            stack.pop_back();
            continue;
        }
        const Bvh2Node& n = bvh.nodes[p.node];
        p.written = uint32_t(out.nodes.size());
        out.nodes.push_back({n.box, 0, n.first, n.count});
        if (n.count == 0) {
            out.nodes.back().first = 0;
            const uint32_t left = n.first;
            stack.push_back({left + 1, UINT32_MAX});
            stack.push_back({left, UINT32_MAX});
        }
    }
    return out;
}

} // namespace wideray
