#include "accel/bvh_stats.h"

#include <algorithm>

namespace wideray {
namespace {

void visitBinary(const BinaryBvh& bvh, const BvhBuildConfig& config, uint32_t index, int depth, float rootArea,
                 BvhStats& s) {
    const BinaryNode& node = bvh.nodes[index];
    double relArea = rootArea > 0 ? node.bounds.area() / rootArea : 1.0;
    if (node.isLeaf()) {
        uint32_t blocks = (node.count + config.blockSize - 1) / config.blockSize;
        ++s.leaves;
        s.leafItems += blocks;
        s.sahCost += config.intersectionCost * blocks * relArea;
        s.depth = std::max(s.depth, depth);
        return;
    }
    ++s.innerNodes;
    s.sahCost += config.traversalCost * relArea;
    visitBinary(bvh, config, node.first, depth + 1, rootArea, s);
    visitBinary(bvh, config, node.first + 1, depth + 1, rootArea, s);
}

template <int N>
float childArea(const WideNode<N>& node, int i) {
    return Bounds3f({node.lowerX[i], node.lowerY[i], node.lowerZ[i]}, {node.upperX[i], node.upperY[i], node.upperZ[i]})
        .area();
}

template <int N>
void visitWide(const WideBvh<N>& bvh, const BvhBuildConfig& config, NodeRef ref, float area, int depth,
               float rootArea, BvhStats& s) {
    double relArea = rootArea > 0 ? area / rootArea : 1.0;
    if (ref.isLeaf()) {
        if (ref.count() == 0) return;
        ++s.leaves;
        s.leafItems += ref.count();
        s.sahCost += config.intersectionCost * ref.count() * relArea;
        s.depth = std::max(s.depth, depth);
        return;
    }
    ++s.innerNodes;
    s.sahCost += config.traversalCost * relArea;
    const WideNode<N>& node = bvh.nodes[ref.index()];
    for (int i = 0; i < N; ++i) s.children += node.child[i].bits != NodeRef::empty().bits;
    for (int i = 0; i < N; ++i) visitWide(bvh, config, node.child[i], childArea(node, i), depth + 1, rootArea, s);
}

} // namespace

BvhStats binaryBvhStats(const BinaryBvh& bvh, const BvhBuildConfig& config) {
    BvhStats s;
    visitBinary(bvh, config, 0, 0, bvh.nodes[0].bounds.area(), s);
    return s;
}

template <int N>
BvhStats wideBvhStats(const WideBvh<N>& bvh, const BvhBuildConfig& config) {
    BvhStats s;
    float rootArea = bvh.bounds.area();
    visitWide(bvh, config, bvh.root, rootArea, 0, rootArea, s);
    return s;
}

template BvhStats wideBvhStats<4>(const WideBvh<4>&, const BvhBuildConfig&);
template BvhStats wideBvhStats<8>(const WideBvh<8>&, const BvhBuildConfig&);
template BvhStats wideBvhStats<16>(const WideBvh<16>&, const BvhBuildConfig&);

} // namespace wideray
