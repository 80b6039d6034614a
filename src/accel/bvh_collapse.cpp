#include "accel/wide_bvh.h"

#include <algorithm>
#include <limits>

namespace wideray {
namespace {

template <int N>
class Collapser {
public:
    Collapser(const BinaryBvh& binary, const LeafEmitter& emitLeaf, WideBvh<N>& out)
        : binary_(binary), emitLeaf_(emitLeaf), out_(out) {}

    void run() {
        const BinaryNode& root = binary_.nodes[0];
        out_.bounds = root.bounds;
        if (root.isLeaf()) {
            out_.root = makeLeaf(root);
            return;
        }
        out_.nodes.emplace_back();
        out_.root = NodeRef::inner(0);
        fillNode(0, 0);
    }

private:
    NodeRef makeLeaf(const BinaryNode& node) {
        std::span<const uint32_t> prims(binary_.primIndices.data() + node.first, node.count);
        uint32_t count = 0;
        uint32_t first = emitLeaf_(prims, count);
        return NodeRef::leaf(first, count);
    }

    void fillNode(uint32_t wideIndex, uint32_t binaryIndex) {
        // Open the largest inner child until there are N children.
        uint32_t children[N];
        int childCount = 2;
        children[0] = binary_.nodes[binaryIndex].first;
        children[1] = children[0] + 1;
        while (childCount < N) {
            int largest = -1;
            float largestArea = -1.0f;
            for (int i = 0; i < childCount; ++i) {
                const BinaryNode& c = binary_.nodes[children[i]];
                if (!c.isLeaf() && c.bounds.area() > largestArea) {
                    largest = i;
                    largestArea = c.bounds.area();
                }
            }
            if (largest < 0) break;
            uint32_t opened = children[largest];
            children[largest] = binary_.nodes[opened].first;
            children[childCount++] = binary_.nodes[opened].first + 1;
        }

        // Inner children get adjacent slots in the node array before any of them is filled.
        int innerCount = 0;
        for (int i = 0; i < childCount; ++i) innerCount += binary_.nodes[children[i]].isLeaf() ? 0 : 1;
        uint32_t nextInner = uint32_t(out_.nodes.size());
        out_.nodes.resize(out_.nodes.size() + innerCount);

        WideNode<N> node;
        constexpr float inf = std::numeric_limits<float>::infinity();
        for (int i = 0; i < N; ++i) {
            node.lowerX[i] = node.lowerY[i] = node.lowerZ[i] = inf;
            node.upperX[i] = node.upperY[i] = node.upperZ[i] = -inf;
            node.child[i] = NodeRef::empty();
        }
        uint32_t pending[N];
        int pendingCount = 0;
        for (int i = 0; i < childCount; ++i) {
            const BinaryNode& c = binary_.nodes[children[i]];
            node.lowerX[i] = c.bounds.lower.x;
            node.lowerY[i] = c.bounds.lower.y;
            node.lowerZ[i] = c.bounds.lower.z;
            node.upperX[i] = c.bounds.upper.x;
            node.upperY[i] = c.bounds.upper.y;
            node.upperZ[i] = c.bounds.upper.z;
            if (c.isLeaf()) {
                node.child[i] = makeLeaf(c);
            } else {
                node.child[i] = NodeRef::inner(nextInner + pendingCount);
                pending[pendingCount++] = children[i];
            }
        }
        out_.nodes[wideIndex] = node;
        for (int i = 0; i < pendingCount; ++i) fillNode(nextInner + i, pending[i]);
    }

    const BinaryBvh& binary_;
    const LeafEmitter& emitLeaf_;
    WideBvh<N>& out_;
};

} // namespace

template <int N>
WideBvh<N> collapseBvh(const BinaryBvh& binary, const LeafEmitter& emitLeaf) {
    WideBvh<N> out;
    out.nodes.reserve(binary.nodes.size() / (N - 1) + 1);
    Collapser<N>(binary, emitLeaf, out).run();
    return out;
}

template WideBvh<4> collapseBvh<4>(const BinaryBvh&, const LeafEmitter&);
template WideBvh<8> collapseBvh<8>(const BinaryBvh&, const LeafEmitter&);

} // namespace wideray
