#include "accel/wide_bvh.h"

#include <algorithm>
#include <limits>

namespace wideray {
namespace {

template <int N>
WideNode<N> emptyNode() {
    WideNode<N> node;
    constexpr float inf = std::numeric_limits<float>::infinity();
    for (int i = 0; i < N; ++i) {
        node.lowerX[i] = node.lowerY[i] = node.lowerZ[i] = inf;
        node.upperX[i] = node.upperY[i] = node.upperZ[i] = -inf;
        node.child[i] = NodeRef::empty();
    }
    return node;
}

template <int N>
void setChildBounds(WideNode<N>& node, int i, const Bounds3f& b) {
    node.lowerX[i] = b.lower.x;
    node.lowerY[i] = b.lower.y;
    node.lowerZ[i] = b.lower.z;
    node.upperX[i] = b.upper.x;
    node.upperY[i] = b.upper.y;
    node.upperZ[i] = b.upper.z;
}

/// Writes wide node `wideIndex` with `children` (binary nodes) in its slots: `isLeaf(b)` says which
/// become leaves, `makeLeaf(b)` emits one, `fill(wideIndex, b)` builds an inner child's node. Inner
/// children get adjacent slots in the node array before any of them is filled.
template <int N, class IsLeaf, class MakeLeaf, class Fill>
void writeWideNode(const BinaryBvh& binary, WideBvh<N>& out, uint32_t wideIndex, const uint32_t* children,
                   int childCount, IsLeaf isLeaf, MakeLeaf makeLeaf, Fill fill) {
    int innerCount = 0;
    for (int i = 0; i < childCount; ++i) innerCount += isLeaf(children[i]) ? 0 : 1;
    const uint32_t nextInner = uint32_t(out.nodes.size());
    out.nodes.resize(out.nodes.size() + innerCount);

    WideNode<N> node = emptyNode<N>();
    uint32_t pending[N];
    int pendingCount = 0;
    for (int i = 0; i < childCount; ++i) {
        setChildBounds(node, i, binary.nodes[children[i]].bounds);
        if (isLeaf(children[i])) {
            node.child[i] = makeLeaf(children[i]);
        } else {
            node.child[i] = NodeRef::inner(nextInner + pendingCount);
            pending[pendingCount++] = children[i];
        }
    }
    out.nodes[wideIndex] = node;
    for (int i = 0; i < pendingCount; ++i) fill(nextInner + i, pending[i]);
}

/// The greedy collapse: each wide node takes the binary node's children and keeps opening the one
/// with the largest surface area until it has N.
template <int N>
class GreedyCollapser {
public:
    GreedyCollapser(const BinaryBvh& binary, const LeafEmitter& emitLeaf, WideBvh<N>& out)
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

        writeWideNode<N>(
            binary_, out_, wideIndex, children, childCount, [&](uint32_t b) { return binary_.nodes[b].isLeaf(); },
            [&](uint32_t b) { return makeLeaf(binary_.nodes[b]); }, [&](uint32_t w, uint32_t b) { fillNode(w, b); });
    }

    const BinaryBvh& binary_;
    const LeafEmitter& emitLeaf_;
    WideBvh<N>& out_;
};

/// The collapse that minimizes the SAH cost of the wide tree (Ylitie, Karras and Laine 2017, "Efficient
/// Incoherent Ray Traversal on GPUs Through Compressed Wide BVHs", section 4): dynamic programming over
/// the binary tree decides, for every binary node, whether it becomes a leaf (its whole subtree's
/// primitives re-packed into blocks), a wide node, or is dissolved so that its children take slots of
/// the wide node above.
template <int N>
class SahCollapser {
public:
    SahCollapser(const BinaryBvh& binary, const LeafEmitter& emitLeaf, const BvhBuildConfig& config, WideBvh<N>& out)
        : binary_(binary), emitLeaf_(emitLeaf), config_(config), out_(out), nodes_(binary.nodes.size()) {}

    void run() {
        solve();
        const BinaryNode& root = binary_.nodes[0];
        out_.bounds = root.bounds;
        if (root.isLeaf() || nodes_[0].leaf) {
            out_.root = makeLeaf(0);
            return;
        }
        out_.nodes.emplace_back();
        out_.root = NodeRef::inner(0);
        fillNode(0, 0);
    }

private:
    /// What the dynamic program knows of one binary node.
    struct Plan {
        uint32_t begin = 0, count = 0;  ///< the subtree's primitives, contiguous in primIndices
        bool leaf = false;              ///< as a child slot: a leaf (else a wide node)
        float slot = 0;                 ///< the subtree's cost in one child slot
        float forest[N + 1];            ///< forest[j]: its cost in at most j slots (j >= 1)
        uint8_t split[N + 1];           ///< forest[j] splits into (split[j], j - split[j]) of the children; 0: one slot
        uint8_t nodeSplit = 0;          ///< as a wide node: its N slots split (nodeSplit, N - nodeSplit) between the children
    };

    uint32_t blocksOf(uint32_t count) const {
        return (count + uint32_t(config_.blockSize) - 1) / uint32_t(config_.blockSize);
    }

    /// Children before parents: the builder numbers every node's children after the node itself.
    void solve() {
        // A leaf made of a dissolved subtree holds at most this many blocks (and at most what one wide
        // leaf can address).
        const uint32_t maxMergedBlocks = std::min<uint32_t>(NodeRef::kMaxLeafItems, 4);
        for (size_t i = binary_.nodes.size(); i-- > 0;) {
            const BinaryNode& node = binary_.nodes[i];
            Plan& plan = nodes_[i];
            const float area = node.bounds.area();
            if (node.isLeaf()) {
                plan.begin = node.first;
                plan.count = node.count;
                plan.leaf = true;
                plan.slot = config_.intersectionCost * float(blocksOf(node.count)) * area;
                for (int j = 1; j <= N; ++j) plan.forest[j] = plan.slot, plan.split[j] = 0;
                continue;
            }
            const Plan &l = nodes_[node.first], &r = nodes_[node.first + 1];
            plan.begin = l.begin;
            plan.count = l.count + r.count;
            float inner = std::numeric_limits<float>::infinity();
            for (int k = 1; k < N; ++k)
                if (l.forest[k] + r.forest[N - k] < inner) {
                    inner = l.forest[k] + r.forest[N - k];
                    plan.nodeSplit = uint8_t(k);
                }
            inner += config_.traversalCost * area;
            const uint32_t blocks = blocksOf(plan.count);
            const float leaf = blocks <= maxMergedBlocks ? config_.intersectionCost * float(blocks) * area
                                                         : std::numeric_limits<float>::infinity();
            plan.leaf = leaf <= inner;
            plan.slot = plan.leaf ? leaf : inner;
            plan.forest[1] = plan.slot;
            plan.split[1] = 0;
            for (int j = 2; j <= N; ++j) {
                plan.forest[j] = plan.slot;
                plan.split[j] = 0;
                for (int k = 1; k < j; ++k)
                    if (l.forest[k] + r.forest[j - k] < plan.forest[j]) {
                        plan.forest[j] = l.forest[k] + r.forest[j - k];
                        plan.split[j] = uint8_t(k);
                    }
            }
        }
    }

    /// The binary nodes that take the `slots` child slots of subtree `index`, as the plan splits it.
    void expand(uint32_t index, int slots, uint32_t* children, int& count) const {
        const Plan& plan = nodes_[index];
        if (plan.split[slots] == 0) {
            children[count++] = index;
            return;
        }
        const uint32_t left = binary_.nodes[index].first;
        expand(left, plan.split[slots], children, count);
        expand(left + 1, slots - plan.split[slots], children, count);
    }

    NodeRef makeLeaf(uint32_t index) {
        const Plan& plan = nodes_[index];
        std::span<const uint32_t> prims(binary_.primIndices.data() + plan.begin, plan.count);
        uint32_t count = 0;
        const uint32_t first = emitLeaf_(prims, count);
        return NodeRef::leaf(first, count);
    }

    void fillNode(uint32_t wideIndex, uint32_t binaryIndex) {
        uint32_t children[N];
        int childCount = 0;
        const uint32_t left = binary_.nodes[binaryIndex].first;
        const int split = nodes_[binaryIndex].nodeSplit;
        expand(left, split, children, childCount);
        expand(left + 1, N - split, children, childCount);

        writeWideNode<N>(
            binary_, out_, wideIndex, children, childCount, [&](uint32_t b) { return nodes_[b].leaf; },
            [&](uint32_t b) { return makeLeaf(b); }, [&](uint32_t w, uint32_t b) { fillNode(w, b); });
    }

    const BinaryBvh& binary_;
    const LeafEmitter& emitLeaf_;
    const BvhBuildConfig& config_;
    WideBvh<N>& out_;
    std::vector<Plan> nodes_;
};

} // namespace

template <int N>
WideBvh<N> collapseBvh(const BinaryBvh& binary, const LeafEmitter& emitLeaf, const BvhBuildConfig& config) {
    WideBvh<N> out;
    out.nodes.reserve(binary.nodes.size() / (N - 1) + 1);
    if (config.collapse == CollapseMethod::Sah) SahCollapser<N>(binary, emitLeaf, config, out).run();
    else GreedyCollapser<N>(binary, emitLeaf, out).run();
    return out;
}

template WideBvh<4> collapseBvh<4>(const BinaryBvh&, const LeafEmitter&, const BvhBuildConfig&);
template WideBvh<8> collapseBvh<8>(const BinaryBvh&, const LeafEmitter&, const BvhBuildConfig&);

} // namespace wideray
