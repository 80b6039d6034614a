#include "accel/wide_bvh.h"
#include "core/default_init_allocator.h"

#include <algorithm>
#include <limits>

#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>

namespace wideray {
namespace {

/// Above this depth the collapse's passes recurse as tasks: as many levels (at most 8) as leave tasks
/// of 4096 binary nodes or more. A small tree runs on one thread: waking the others for tasks of a few
/// microseconds cost more than it gained (the teapot's fast build 0.75 -> 0.59 ms, the dragon's 13.0
/// -> 12.2).
int taskDepth(size_t binaryNodes) {
    int depth = 0;
    while (depth < 8 && binaryNodes >> depth >= 8192) ++depth;
    return depth;
}

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

/// Writes the wide tree a collapse decided, described by its Shape: isLeaf(b) says which binary
/// nodes become wide leaves, prims(b) their primitives, children(b, out) the binary nodes in the
/// slots of the wide node b becomes. A first pass counts every wide subtree's nodes and leaf items,
/// so that the second can write subtrees in parallel at their final places: each wide node's inner
/// children adjacent, its leaves' items first, then its inner children's subtrees in slot order.
template <int N, class Shape>
class WideTreeWriter {
public:
    WideTreeWriter(const BinaryBvh& binary, const Shape& shape, LeafWriter& leaves, WideBvh<N>& out)
        : binary_(binary), shape_(shape), leaves_(leaves), out_(out), sizes_(binary.nodes.size()),
          taskDepth_(taskDepth(binary.nodes.size())) {}

    void run() {
        out_.bounds = binary_.nodes[0].bounds;
        if (shape_.isLeaf(0)) {
            const uint32_t items = leaves_.itemCount(shape_.prims(0));
            leaves_.allocate(items);
            leaves_.write(shape_.prims(0), 0);
            out_.root = NodeRef::leaf(0, items);
            return;
        }
        const Size total = count(0, 0);
        out_.nodes.resize(total.nodes);
        leaves_.allocate(total.items);
        out_.root = NodeRef::inner(0);
        fill(0, 0, 1, 0, 0);
    }

private:
    /// Of a wide subtree: its wide nodes; of a wide leaf: nothing. Both: the leaf items.
    struct Size {
        uint32_t nodes, items;
    };

    template <class F>
    void forEach(int count, int depth, F f) const {
        if (depth < taskDepth_) tbb::parallel_for(0, count, f);
        else
            for (int i = 0; i < count; ++i) f(i);
    }

    Size count(uint32_t b, int depth) {
        uint32_t children[N];
        const int childCount = shape_.children(b, children);
        forEach(childCount, depth, [&](int i) {
            const uint32_t c = children[i];
            if (shape_.isLeaf(c)) sizes_[c] = {0, leaves_.itemCount(shape_.prims(c))};
            else count(c, depth + 1);
        });
        Size s{1, 0};
        for (int i = 0; i < childCount; ++i) {
            s.nodes += sizes_[children[i]].nodes;
            s.items += sizes_[children[i]].items;
        }
        sizes_[b] = s;
        return s;
    }

    /// Writes wide node `wideIndex` for binary node b; its inner children go to nextNode on, its
    /// items to nextItem on.
    void fill(uint32_t wideIndex, uint32_t b, uint32_t nextNode, uint32_t nextItem, int depth) {
        uint32_t children[N];
        const int childCount = shape_.children(b, children);
        WideNode<N> node = emptyNode<N>();
        uint32_t inner[N], innerNode[N], innerItem[N];
        int innerCount = 0;
        for (int i = 0; i < childCount; ++i) innerCount += shape_.isLeaf(children[i]) ? 0 : 1;
        uint32_t descendants = nextNode + uint32_t(innerCount);
        int k = 0;
        for (int i = 0; i < childCount; ++i) {
            const uint32_t c = children[i];
            setChildBounds(node, i, binary_.nodes[c].bounds);
            if (shape_.isLeaf(c)) {
                leaves_.write(shape_.prims(c), nextItem);
                node.child[i] = NodeRef::leaf(nextItem, sizes_[c].items);
                nextItem += sizes_[c].items;
            } else {
                node.child[i] = NodeRef::inner(nextNode + uint32_t(k));
                inner[k] = c;
                innerNode[k] = descendants;
                descendants += sizes_[c].nodes - 1;
                ++k;
            }
        }
        for (int j = 0; j < innerCount; ++j) {
            innerItem[j] = nextItem;
            nextItem += sizes_[inner[j]].items;
        }
        out_.nodes[wideIndex] = node;
        forEach(innerCount, depth, [&](int j) {
            fill(nextNode + uint32_t(j), inner[j], innerNode[j], innerItem[j], depth + 1);
        });
    }

    const BinaryBvh& binary_;
    const Shape& shape_;
    LeafWriter& leaves_;
    WideBvh<N>& out_;
    UninitializedVector<Size> sizes_;  ///< by binary node, for those that become wide nodes or leaves
    int taskDepth_;
};

/// The greedy collapse: each wide node takes the binary node's children and keeps opening the one
/// with the largest surface area until it has N.
template <int N>
struct GreedyShape {
    const BinaryBvh& binary;

    bool isLeaf(uint32_t b) const { return binary.nodes[b].isLeaf(); }
    std::span<const uint32_t> prims(uint32_t b) const {
        return {binary.primIndices.data() + binary.nodes[b].first, binary.nodes[b].count};
    }
    int children(uint32_t b, uint32_t* out) const {
        int count = 2;
        out[0] = binary.nodes[b].first;
        out[1] = out[0] + 1;
        while (count < N) {
            int largest = -1;
            float largestArea = -1.0f;
            for (int i = 0; i < count; ++i) {
                const BinaryNode& c = binary.nodes[out[i]];
                if (!c.isLeaf() && c.bounds.area() > largestArea) {
                    largest = i;
                    largestArea = c.bounds.area();
                }
            }
            if (largest < 0) break;
            const uint32_t opened = out[largest];
            out[largest] = binary.nodes[opened].first;
            out[count++] = binary.nodes[opened].first + 1;
        }
        return count;
    }
};

/// The collapse that minimizes the SAH cost of the wide tree (Ylitie, Karras and Laine 2017, "Efficient
/// Incoherent Ray Traversal on GPUs Through Compressed Wide BVHs", section 4): dynamic programming over
/// the binary tree decides, for every binary node, whether it becomes a leaf (its whole subtree's
/// primitives re-packed into blocks), a wide node, or is dissolved so that its children take slots of
/// the wide node above.
template <int N>
class SahShape {
public:
    SahShape(const BinaryBvh& binary, const BvhBuildConfig& config)
        : binary_(binary), config_(config), plans_(binary.nodes.size()), taskDepth_(taskDepth(binary.nodes.size())) {
        solve(0, 0);
    }

    bool isLeaf(uint32_t b) const { return plans_[b].leaf; }
    std::span<const uint32_t> prims(uint32_t b) const {
        return {binary_.primIndices.data() + plans_[b].begin, plans_[b].count};
    }
    int children(uint32_t b, uint32_t* out) const {
        int count = 0;
        const uint32_t left = binary_.nodes[b].first;
        const int split = plans_[b].nodeSplit;
        expand(left, split, out, count);
        expand(left + 1, N - split, out, count);
        return count;
    }

private:
    /// What the dynamic program decided for one binary node (20 bytes for N = 8: there are as many as
    /// binary nodes, and each is written once and read by the tree's writer). Left uninitialized until
    /// solve() writes it.
    struct Plan {
        uint32_t begin, count;  ///< the subtree's primitives, contiguous in primIndices
        bool leaf;              ///< as a child slot: a leaf (else a wide node)
        uint8_t nodeSplit;      ///< as a wide node: its N slots split (nodeSplit, N - nodeSplit) between the children
        uint8_t split[N + 1];   ///< in at most j slots it splits into (split[j], j - split[j]) of the children; 0: one slot
    };
    static_assert(sizeof(Plan) == 4 * ((10 + N + 1 + 3) / 4));
    /// A subtree's costs, which only its parent reads: cost[j] in at most j slots (j >= 1); cost[1] is
    /// its cost in one child slot.
    struct Forest {
        float cost[N + 1];
    };

    uint32_t blocksOf(uint32_t count) const {
        return (count + uint32_t(config_.blockSize) - 1) / uint32_t(config_.blockSize);
    }

    /// Children before parents, the two subtrees as tasks near the root.
    Forest solve(uint32_t i, int depth) {
        const BinaryNode& node = binary_.nodes[i];
        Plan& plan = plans_[i];
        const float area = node.bounds.area();
        Forest forest;
        if (node.isLeaf()) {
            plan.begin = node.first;
            plan.count = node.count;
            plan.leaf = true;
            plan.nodeSplit = 0;
            const float slot = config_.intersectionCost * float(blocksOf(node.count)) * area;
            for (int j = 1; j <= N; ++j) forest.cost[j] = slot, plan.split[j] = 0;
            return forest;
        }
        Forest l, r;
        if (depth < taskDepth_)
            tbb::parallel_invoke([&] { l = solve(node.first, depth + 1); }, [&] { r = solve(node.first + 1, depth + 1); });
        else {
            l = solve(node.first, depth + 1);
            r = solve(node.first + 1, depth + 1);
        }
        // A leaf made of a dissolved subtree holds at most this many blocks (and at most what one wide
        // leaf can address).
        const uint32_t maxMergedBlocks = std::min<uint32_t>(NodeRef::kMaxLeafItems, 4);
        plan.begin = plans_[node.first].begin;
        plan.count = plans_[node.first].count + plans_[node.first + 1].count;
        // Two leaves cost the same in any number of slots: the loops below have one answer, their first.
        const bool twoLeaves = binary_.nodes[node.first].isLeaf() && binary_.nodes[node.first + 1].isLeaf();
        const float bothLeaves = l.cost[1] + r.cost[1];
        float inner = std::numeric_limits<float>::infinity();
        if (twoLeaves) {
            inner = bothLeaves;
            plan.nodeSplit = 1;
        } else {
            for (int k = 1; k < N; ++k)
                if (l.cost[k] + r.cost[N - k] < inner) {
                    inner = l.cost[k] + r.cost[N - k];
                    plan.nodeSplit = uint8_t(k);
                }
        }
        inner += config_.traversalCost * area;
        const uint32_t blocks = blocksOf(plan.count);
        const float leaf = blocks <= maxMergedBlocks ? config_.intersectionCost * float(blocks) * area
                                                     : std::numeric_limits<float>::infinity();
        plan.leaf = leaf <= inner;
        forest.cost[1] = plan.leaf ? leaf : inner;
        plan.split[1] = 0;
        if (twoLeaves) {
            for (int j = 2; j <= N; ++j) {
                forest.cost[j] = bothLeaves < forest.cost[1] ? bothLeaves : forest.cost[1];
                plan.split[j] = bothLeaves < forest.cost[1] ? 1 : 0;
            }
            return forest;
        }
        for (int j = 2; j <= N; ++j) {
            forest.cost[j] = forest.cost[1];
            plan.split[j] = 0;
            for (int k = 1; k < j; ++k)
                if (l.cost[k] + r.cost[j - k] < forest.cost[j]) {
                    forest.cost[j] = l.cost[k] + r.cost[j - k];
                    plan.split[j] = uint8_t(k);
                }
        }
        return forest;
    }

    /// The binary nodes that take the `slots` child slots of subtree `index`, as the plan splits it.
    void expand(uint32_t index, int slots, uint32_t* children, int& count) const {
        const Plan& plan = plans_[index];
        if (plan.split[slots] == 0) {
            children[count++] = index;
            return;
        }
        const uint32_t left = binary_.nodes[index].first;
        expand(left, plan.split[slots], children, count);
        expand(left + 1, slots - plan.split[slots], children, count);
    }

    const BinaryBvh& binary_;
    const BvhBuildConfig& config_;
    UninitializedVector<Plan> plans_;
    int taskDepth_;
};

} // namespace

template <int N>
WideBvh<N> collapseBvh(const BinaryBvh& binary, LeafWriter& leaves, const BvhBuildConfig& config) {
    WideBvh<N> out;
    if (config.collapse == CollapseMethod::Sah) {
        const SahShape<N> shape(binary, config);
        WideTreeWriter<N, SahShape<N>>(binary, shape, leaves, out).run();
    } else {
        const GreedyShape<N> shape{binary};
        WideTreeWriter<N, GreedyShape<N>>(binary, shape, leaves, out).run();
    }
    return out;
}

template WideBvh<4> collapseBvh<4>(const BinaryBvh&, LeafWriter&, const BvhBuildConfig&);
template WideBvh<8> collapseBvh<8>(const BinaryBvh&, LeafWriter&, const BvhBuildConfig&);
template WideBvh<16> collapseBvh<16>(const BinaryBvh&, LeafWriter&, const BvhBuildConfig&);

} // namespace wideray
