#pragma once
// Binary BVH built with the binned surface area heuristic (Wald 2007, "On fast construction of
// SAH-based bounding volume hierarchies"), with spatial splits at high quality (Stich et al. 2009). It
// is the input of the wide collapse, not a tracing layout.
#include <cstddef>
#include <cstdint>
#include <new>
#include <utility>
#include <vector>

#include "accel/build_ref.h"
#include "core/bounds.h"
#include "core/default_init_allocator.h"
#include "wideray/options.h"

namespace wideray {

struct BinaryNode {
    Bounds3f bounds;
    uint32_t first = 0;  ///< leaf: first entry of primIndices; inner: left child (right is first + 1)
    uint32_t count = 0;  ///< primitives in a leaf; 0 for an inner node

    bool isLeaf() const { return count > 0; }
};

/// A binary BVH's nodes, in memory sized for the most nodes a build may create, of which it touches
/// only those it creates: a vector would construct them all up front, or cost a copy (and the page
/// faults of its fresh memory) once their number is known.
class BinaryNodes {
public:
    BinaryNodes() = default;
    BinaryNodes(BinaryNodes&& other) noexcept
        : storage_(std::move(other.storage_)), size_(std::exchange(other.size_, 0)) {}
    BinaryNodes& operator=(BinaryNodes&& other) noexcept {
        storage_ = std::move(other.storage_);
        size_ = std::exchange(other.size_, 0);
        return *this;
    }
    BinaryNodes(const BinaryNodes&) = delete;  // would copy the whole capacity, untouched pages too
    BinaryNodes& operator=(const BinaryNodes&) = delete;

    /// Room for `capacity` nodes, none of them in use (the builder places its nodes there).
    void allocate(size_t capacity) {
        storage_.resize(capacity * sizeof(BinaryNode));
        size_ = 0;
    }
    /// The first `count` nodes are in use (count <= the capacity allocated).
    void setSize(size_t count) { size_ = count; }

    BinaryNode* data() { return std::launder(reinterpret_cast<BinaryNode*>(storage_.data())); }
    const BinaryNode* data() const { return std::launder(reinterpret_cast<const BinaryNode*>(storage_.data())); }
    size_t size() const { return size_; }
    size_t capacity() const { return storage_.size() / sizeof(BinaryNode); }
    BinaryNode& operator[](size_t i) { return data()[i]; }
    const BinaryNode& operator[](size_t i) const { return data()[i]; }
    const BinaryNode* begin() const { return data(); }
    const BinaryNode* end() const { return data() + size_; }

private:
    UninitializedVector<std::byte> storage_;
    size_t size_ = 0;
};

struct BinaryBvh {
    BinaryNodes nodes;  ///< nodes[0] is the root
    UninitializedVector<uint32_t> primIndices;  ///< leaves' primitives; a subtree's are contiguous
};

enum class SplitMethod { Sah, Median };

/// How the binary tree becomes a wide one: the SAH-optimal collapse (dynamic programming), or greedily
/// opening the largest child until a node has N.
enum class CollapseMethod { Sah, Greedy };

// BuildQuality (wideray/options.h), Fast: object splits only, each primitive in one leaf. High: spatial
// splits too, which clip primitives so that one may be referenced by several leaves (within
// replicationBudget).

class TriangleSplitter;

struct BvhBuildConfig {
    SplitMethod split = SplitMethod::Sah;
    CollapseMethod collapse = CollapseMethod::Sah;
    int binCount = 32;
    int maxLeafSize = 8;
    /// Leaves are intersected in blocks of this many primitives (a power of two), so the SAH charges
    /// whole blocks.
    int blockSize = 1;
    float traversalCost = 1.0f;
    float intersectionCost = 1.0f;
    BuildQuality quality = BuildQuality::Fast;
    /// High quality: at most this many extra references, as a fraction of the primitives (Embree: 0.2).
    float replicationBudget = 0.2f;
    /// Spatial bins per axis. 8 against Embree's 16: the same SAH cost on the shared meshes (lower on
    /// Sponza and the kitchen, +0.3% on the dragon), trace speed the same within noise (interiors,
    /// single, packet16 and stream, two rounds), 10% less build time.
    int spatialBinCount = 8;
    /// High quality: spatial splits are tried where the best object split's children overlap by more
    /// than this fraction of the root's area (Stich et al.'s alpha). 1e-4 against the paper's 1e-5:
    /// the same SAH cost on every shared mesh and interior scene (8- and 16-wide), fewer references
    /// (the kitchen's 1.044 -> 1.031 per triangle, the coffee maker's 1.027 -> 1.015), the high build
    /// 10% faster on the kitchen, 15% on the coffee maker, 5% on Sponza (`wideray info --quality high`,
    /// 8 alternated pairs). 1e-3: 20-29% faster, but SAH costs up to 0.25% higher (the coffee maker,
    /// which it leaves without spatial splits; Sponza 20.51 -> 20.54).
    float spatialOverlap = 1e-4f;
    /// ... and by more than this fraction of the node's own area (Embree's second test: where the
    /// object split's children barely overlap, clipping cannot gain much).
    float spatialNodeOverlap = 0.1f;
    /// High quality: nodes with fewer references use object splits only. Measured on Sponza, the
    /// country kitchen and the bunny: the same SAH cost as spatial splits everywhere, half the build
    /// time on the bunny.
    int spatialMinRefs = 256;
    /// High quality, below this many triangles: the fast build is made too and kept if its wide tree
    /// costs less (it did on Suzanne, the teapot and the Cornell box). Above it, spatial splits won on
    /// every mesh measured (the bunny narrowly; tests/test_bvh.cpp checks the shared meshes), and the
    /// second build would add half the time.
    size_t compareBuildsBelow = size_t(1) << 15;
    /// High quality, below this many primitives: the binary tree is split down to single primitives
    /// and the collapse's dynamic program chooses the leaves. The binary build's own leaf test charges
    /// every split a traversal step, which a wide node's children do not cost, so it keeps nodes of a
    /// few large triangles (two walls of a room) together. The Cornell box's SAH cost 5.12 -> 3.64,
    /// its camera rays (packet16) 1.37x faster; Suzanne 6.82 -> 6.09; but the build takes twice as
    /// long (the bunny 12.5 -> 21.7 ms at high quality, for 4-9% faster rays), which larger meshes do
    /// not get.
    size_t singlePrimLeavesBelow = size_t(1) << 12;
    /// Nodes of at least this many references partition them on all threads (with the same result).
    uint32_t parallelPartitionMinRefs = 1u << 16;
};

/// The deepest a build goes; past kMedianDepth it splits at the object median, which bounds the depth.
constexpr int kMaxBvhDepth = 64;

/// The references a build over `primCount` primitives may use: with the spatial splits' duplicates.
/// Callers that reserve it spare the build a copy of the references (and its page faults).
size_t buildRefCapacity(size_t primCount, const BvhBuildConfig& config);

/// The fewest references a node split spatially has (none at fast quality). A node's references name
/// distinct primitives (a spatial split sends one copy to each side), so a subtree of fewer
/// references names each primitive once, as a leaf the collapse makes of it does.
size_t minSpatialSplitRefs(const BvhBuildConfig& config);

/// Builds over one reference per primitive (at least one; ref.prim its index). At high quality the
/// splitter clips primitives (without one the build is the fast one). Parallel with oneTBB; the
/// tree's shape does not depend on the thread count.
BinaryBvh buildBinaryBvh(BuildRefs refs, const BvhBuildConfig& config,
                         const TriangleSplitter* splitter = nullptr);

} // namespace wideray
