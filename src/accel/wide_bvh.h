#pragma once
// The N-wide BVH that every kernel traverses: all children of a node are described inside the node,
// child boxes stored per axis (SoA) so that one SIMD operation tests all N children, and the inner
// children of a node are stored next to each other in the node array.
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "accel/bvh_binary.h"
#include "core/default_init_allocator.h"

namespace wideray {

/// A child reference: an inner node's index, or a leaf (kLeafFlag) holding `count` consecutive leaf
/// items starting at `first`. Leaves are of two types, told apart by kUserFlag: triangle blocks, and
/// user primitives (the BVH's owner defines what the items of each are).
struct NodeRef {
    static constexpr uint32_t kLeafFlag = 0x80000000u;
    static constexpr int kCountShift = 27;
    static constexpr uint32_t kMaxLeafItems = 15;
    static constexpr uint32_t kUserFlag = 1u << 26;
    static constexpr uint32_t kFirstMask = kUserFlag - 1;  ///< the most leaf items of one type: 2^26

    uint32_t bits;  ///< left uninitialized by default: traversal stacks hold hundreds of these

    /// An empty leaf: what unused child slots hold.
    static NodeRef empty() { return {kLeafFlag}; }
    static NodeRef inner(uint32_t index) { return {index}; }
    static NodeRef leaf(uint32_t first, uint32_t count) { return {kLeafFlag | (count << kCountShift) | first}; }
    static NodeRef userLeaf(uint32_t first, uint32_t count) { return {leaf(first, count).bits | kUserFlag}; }

    bool isLeaf() const { return bits & kLeafFlag; }
    /// A leaf of user primitives (only meaningful for leaves).
    bool isUserLeaf() const { return bits & kUserFlag; }
    uint32_t index() const { return bits; }
    uint32_t first() const { return bits & kFirstMask; }
    uint32_t count() const { return (bits & ~kLeafFlag) >> kCountShift; }
};

template <int N>
struct alignas(64) WideNode {
    float lowerX[N], upperX[N], lowerY[N], upperY[N], lowerZ[N], upperZ[N];
    NodeRef child[N];

    /// The children's lower or upper bounds on one axis (planes(0, false) = lowerX; empty slots are
    /// [+inf, -inf]). The six arrays lie one after another: an offset, where a table of the six
    /// pointers made the compiler store it on the stack at every call and load it back before the node.
    const float* planes(int axis, bool upper) const { return lowerX + N * (2 * axis + (upper ? 1 : 0)); }
};
static_assert(sizeof(WideNode<4>) == 128);
static_assert(sizeof(WideNode<8>) == 256);
static_assert(sizeof(WideNode<16>) == 448);
static_assert(offsetof(WideNode<8>, upperZ) == 5 * 8 * sizeof(float) &&
                  offsetof(WideNode<16>, upperZ) == 5 * 16 * sizeof(float),
              "WideNode::planes: the six arrays lie one after another");

template <int N>
struct WideBvh {
    UninitializedVector<WideNode<N>> nodes;  ///< every node written whole by the collapse
    NodeRef root = NodeRef::empty();  ///< a leaf when the whole scene fits in one
    Bounds3f bounds;       ///< of the whole tree
};

/// Turns the primitive indices of the wide tree's leaves into leaf items (triangle blocks, say) in an
/// array the collapse sizes once it knows the total; leaves are written concurrently.
class LeafWriter {
public:
    virtual ~LeafWriter() = default;
    /// The items one leaf's primitives take (at most NodeRef::kMaxLeafItems).
    virtual uint32_t itemCount(std::span<const uint32_t> prims) const = 0;
    /// Sizes the item array for `count` items in all.
    virtual void allocate(size_t count) = 0;
    /// Writes one leaf's items from index `first` on; called concurrently for disjoint ranges.
    virtual void write(std::span<const uint32_t> prims, uint32_t first) const = 0;
};

/// Collapses a binary BVH into an N-wide one (N = 4, 8 or 16) as config.collapse says: the wide tree of
/// least SAH cost (config's traversal and intersection costs, blocks of config.blockSize), or greedily.
/// Parallel; the result does not depend on the thread count.
template <int N>
WideBvh<N> collapseBvh(const BinaryBvh& binary, LeafWriter& leaves, const BvhBuildConfig& config);

} // namespace wideray
