#include "accel/bvh_binary.h"

#include <algorithm>
#include <atomic>
#include <cassert>
#include <cstddef>
#include <memory>
#include <new>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>
#include <tbb/parallel_reduce.h>

#include "accel/object_bins.h"
#include "accel/spatial_bins.h"

namespace wideray {
namespace {

constexpr int kMedianDepth = kMaxBvhDepth - 24;  // leaves room for log2(2^24) median levels
constexpr uint32_t kParallelThreshold = 4096;    // references (or samples): above, binning runs in parallel and subtrees as tasks
constexpr uint32_t kParallelGrain = 4096;
// Spatial binning of nodes of at least kSpatialSampleMinRefs references is tried on a sample first
// (spatialAxesToBin), every kSpatialSampleStride-th reference. Measured against binning all
// (`wideray info --quality high`, one thread): the same SAH cost on the coffee maker, the kitchen and
// Sponza (the dragon's +0.1%), the kitchen's build 674 -> 617 ms. Sampling from 256 references instead
// of 2048, and binning all of them only along the axes the sample favours: the kitchen's binary build
// 481 -> 432 ms (minima of 10, alternated), SAH cost 9.97 -> 9.91, Sponza's 20.52 -> 20.51, the
// dragon's, the coffee maker's and the bunny's the same; along every axis the sample's split beats the
// object split on, 8% slower than with the slack below (and the kitchen's SAH cost 9.97).
constexpr uint32_t kSpatialSampleMinRefs = 256;
constexpr uint32_t kSpatialSampleStride = 8;
// Larger nodes are sampled more sparsely, fewer than twice this many references: the same SAH cost on
// every shared mesh (from 8192: Sponza's 20.51 -> 20.81).
constexpr uint32_t kSpatialSampleMaxSize = 16384;
// An axis is binned in full where its sample's best split costs at most this much more than the best
// axis's. 1.1 or 1.2: Sponza's SAH cost 20.64 or 20.61; the best axis alone: 20.69.
constexpr float kSpatialAxisSlack = 1.5f;
// Nodes of at least kObjectSampleMinRefs references choose their object split's plane on a sample,
// every kObjectSampleStride-th reference; one pass then bins them all for the partition and measures
// both sides (measureObjectSplit). Measured on the shared meshes (`wideray info`): SAH costs within
// 0.3% of binning all (the kitchen's high build 9.91 -> 9.93, Sponza's fast build 22.60 -> 22.21), the
// kitchen's high build 8% faster (ABBA, 5 rounds: 5% from 2^16 references on, 3% more from 2^14). A
// sparser sample chose worse planes near the root, where the greedy SAH is fragile (every 8th
// reference from 2^16 on: the kitchen's high build's SAH cost 10.06).
// Nodes of at least this many references bin each reference's parts as its box cut by the bin
// planes, not as the clipped triangle's boxes: their triangles are small against their bins, so the
// parts come out nearly as tight, without clipping. The split itself still clips the triangles.
// Measured (`wideray info --quality high`; `wideray_perf` bvhBuild, 2 threads, ABBA in 4 rounds): SAH
// cost the same on the kitchen (9.93), the coffee maker (3.97) and Sponza (20.51), the dragon's 14.75
// -> 14.86; the high build 6% faster on the kitchen, 12% on the coffee maker, 3% on Sponza. From 4096
// references: no faster, the dragon's 14.89.
constexpr uint32_t kSpatialBoxClipMinRefs = 1u << 14;
constexpr uint32_t kObjectSampleMinRefs = 1u << 14;
constexpr uint32_t kObjectSampleStride = 4;

/// A node's references: [begin, end) in use, [end, capacityEnd) free for the duplicates that spatial
/// splits below it create. Bounds of the references and of their center2.
struct BuildRange {
    uint32_t begin = 0, end = 0, capacityEnd = 0;
    BuildBox bounds, centroids;

    uint32_t size() const { return end - begin; }
    uint32_t spare() const { return capacityEnd - end; }
};

struct RangeBounds {
    BuildBox bounds, centroids;

    void add(const BuildRef* refs, uint32_t begin, uint32_t end) {
        for (uint32_t i = begin; i != end; ++i) {
            const BuildBox box(refs[i]);
            bounds.grow(box);
            centroids.grow(box.center2());
        }
    }
    void merge(const RangeBounds& other) {
        bounds.grow(other.bounds);
        centroids.grow(other.centroids);
    }
};

/// Reduces `add` over [begin, end) into `result` (fresh from `make`), in parallel for large ranges.
/// Exact whatever the split: bins only take minima, maxima and integer counts.
template <class T, class Make, class Add>
void reduceRange(uint32_t begin, uint32_t end, T& result, Make make, Add add) {
    if (end - begin < kParallelThreshold) {
        add(result, begin, end);
        return;
    }
    result = tbb::parallel_reduce(
        tbb::blocked_range<uint32_t>(begin, end, kParallelGrain), make(),
        [&](const tbb::blocked_range<uint32_t>& r, T acc) {
            add(acc, r.begin(), r.end());
            return acc;
        },
        [](T a, const T& b) {
            a.merge(b);
            return a;
        });
}

class Builder {
public:
    Builder(BuildRefs& refs, const BvhBuildConfig& config, const TriangleSplitter* splitter, BinaryBvh& out)
        : refs_(refs), config_(config), splitter_(config.quality == BuildQuality::High ? splitter : nullptr), out_(out),
          toSinglePrims_(config.quality == BuildQuality::High && refs.size() < config.singlePrimLeavesBelow) {}

    void build() {
        const uint32_t primCount = uint32_t(refs_.size());
        const uint32_t capacity = splitter_ ? uint32_t(buildRefCapacity(primCount, config_)) : primCount;
        refs_.resize(capacity);
        // Room for the most nodes a tree over `capacity` references can have, of which the build
        // touches only those it creates.
        out_.nodes.allocate(2 * size_t(capacity) - 1);
        nodes_ = out_.nodes.data();
        if (capacity != primCount) refsBelow_.resize(out_.nodes.capacity());
        nodeCount_ = 1;
        BuildRange root = measured(0, primCount, capacity);
        rootHalfArea_ = root.bounds.halfArea();
        const uint32_t leafRefs = buildNode(0, root, 0);
        out_.nodes.setSize(nodeCount_);
        if (capacity == primCount) {
            // Without spare capacity the leaves tile the references in depth-first order already.
            out_.primIndices.resize(primCount);
            tbb::parallel_for(tbb::blocked_range<uint32_t>(0, primCount, 1u << 16), [&](const tbb::blocked_range<uint32_t>& r) {
                for (uint32_t i = r.begin(); i != r.end(); ++i) out_.primIndices[i] = refs_[i].prim;
            });
        } else {
            out_.primIndices.resize(leafRefs);
            gatherLeaves(0, 0);
        }
    }

private:
    uint32_t blockSize() const { return uint32_t(config_.blockSize); }
    uint32_t blockShift() const { return uint32_t(__builtin_ctz(blockSize())); }
    /// The blocks a leaf of `count` references takes, as the SAH charges them.
    float blocksOf(uint32_t count) const { return float((count + blockSize() - 1) >> blockShift()); }

    BuildRange measured(uint32_t begin, uint32_t end, uint32_t capacityEnd) const {
        RangeBounds b;
        reduceRange(
            begin, end, b, [] { return RangeBounds(); },
            [&](RangeBounds& acc, uint32_t from, uint32_t to) { acc.add(refs_.data(), from, to); });
        return {begin, end, capacityEnd, b.bounds, b.centroids};
    }

    /// Builds the subtree at nodes_[nodeIndex]; returns the number of references in its leaves (kept
    /// in refsBelow_ where spare capacity will leave gaps for gatherLeaves to close).
    uint32_t buildNode(uint32_t nodeIndex, const BuildRange& range, int depth) {
        if (range.size() < kParallelThreshold) return buildLocally(nodeIndex, range, depth);
        BinaryNode& node = *new (&nodes_[nodeIndex]) BinaryNode;
        BuildRange left, right;
        uint32_t refs = range.size();
        if (makeNode(range, depth, node, left, right)) {
            const uint32_t child = nodeCount_.fetch_add(2);
            node.first = child;
            uint32_t leftRefs, rightRefs;
            tbb::parallel_invoke([&] { leftRefs = buildNode(child, left, depth + 1); },
                                 [&] { rightRefs = buildNode(child + 1, right, depth + 1); });
            refs = leftRefs + rightRefs;
        }
        if (!refsBelow_.empty()) refsBelow_[nodeIndex] = refs;
        return refs;
    }

    /// Makes `node` over `range` a leaf (returns false), or splits the range into `left` and `right`
    /// with the spare capacity shared between them; the caller places the children (node.first).
    bool makeNode(const BuildRange& range, int depth, BinaryNode& node, BuildRange& left, BuildRange& right) {
        node.bounds = range.bounds.bounds();
        if (!split(range, depth, left, right)) {
            node.first = range.begin;
            node.count = range.size();
            return false;
        }
        shareSpare(range, left, right);
        return true;
    }

    /// A subtree small enough for one thread, built in that thread's own array and then copied into
    /// nodes_ with one draw on the shared counter. Drawing each pair of children from the counter
    /// made two threads pass its cache line back and forth, and write nodes onto each other's cache
    /// lines, for every node (two threads, alternated: the kitchen's fast build 174-194 -> 157-174 ms,
    /// its high build 278-299 -> 267-281 ms).
    struct LocalSubtree {
        std::vector<BinaryNode> nodes;  ///< [0]: the subtree's root; children after their parents
        std::vector<uint32_t> refsBelow;
        bool inUse = false;
    };

    uint32_t buildLocally(uint32_t nodeIndex, const BuildRange& range, int depth) {
        // Kept by each thread, so that its memory is allocated once (a small subtree runs no tasks,
        // so nothing else on the thread uses it meanwhile; should one, it gets an array of its own).
        thread_local LocalSubtree kept;
        LocalSubtree fresh;
        LocalSubtree& local = kept.inUse ? fresh : kept;
        local.inUse = true;
        struct Release {
            LocalSubtree& local;
            ~Release() { local.inUse = false; }  // also where the build throws (bad_alloc)
        } release{local};
        local.nodes.resize(1);
        local.refsBelow.resize(refsBelow_.empty() ? 0 : 1);
        const uint32_t refs = buildLocalNode(local, 0, range, depth);
        const uint32_t descendants = uint32_t(local.nodes.size()) - 1;
        const uint32_t base = descendants > 0 ? nodeCount_.fetch_add(descendants) - 1 : 0;  // local i >= 1 -> base + i
        for (uint32_t i = 0; i <= descendants; ++i) {
            BinaryNode node = local.nodes[i];
            if (!node.isLeaf()) node.first += base;
            const uint32_t to = i == 0 ? nodeIndex : base + i;
            new (&nodes_[to]) BinaryNode(node);
            if (!refsBelow_.empty()) refsBelow_[to] = local.refsBelow[i];
        }
        return refs;
    }

    /// buildNode within a local subtree: children take the next pair of local.nodes. refsBelow is
    /// kept only where the build keeps refsBelow_ (spare capacity).
    uint32_t buildLocalNode(LocalSubtree& local, uint32_t index, const BuildRange& range, int depth) {
        BinaryNode node;
        BuildRange left, right;
        uint32_t refs = range.size();
        if (makeNode(range, depth, node, left, right)) {
            node.first = uint32_t(local.nodes.size());
            local.nodes.resize(node.first + 2);
            if (!refsBelow_.empty()) local.refsBelow.resize(node.first + 2);
            refs = buildLocalNode(local, node.first, left, depth + 1);
            refs += buildLocalNode(local, node.first + 1, right, depth + 1);
        }
        local.nodes[index] = node;
        if (!refsBelow_.empty()) local.refsBelow[index] = refs;
        return refs;
    }

    /// Splits `range` into two children, or returns false where it becomes a leaf.
    bool split(const BuildRange& range, int depth, BuildRange& left, BuildRange& right) {
        const uint32_t count = range.size();
        if (count == 1) return false;
        const bool fitsLeaf = count <= uint32_t(config_.maxLeafSize) && !toSinglePrims_;
        // One block's leaf costs intersectionCost, any split at least traversalCost: where that is no
        // less, the SAH below would choose the leaf, so it is chosen without binning.
        if (fitsLeaf && count <= blockSize() && config_.traversalCost >= config_.intersectionCost && config_.intersectionCost >= 0)
            return false;
        if (config_.split == SplitMethod::Median || depth >= kMedianDepth) {
            if (fitsLeaf) return false;
            splitAtMedian(range, left, right);
            return true;
        }

        const ObjectBinMapping objectMapping(range.centroids, count, config_.binCount);
        ObjectBins objectBins(objectMapping.count);
        const uint32_t objectStride = count >= kObjectSampleMinRefs ? kObjectSampleStride : 1;
        binEvery(objectStride, range, objectBins, objectMapping);
        objectBins.scaleCounts(objectStride);
        ObjectSplit object = objectBins.bestSplit(objectMapping, blockShift());
        if (objectStride > 1 && object.axis >= 0) measureObjectSplit(range, objectMapping, object);
        // A leaf wins where its cost is no more than that of the split of least cost.
        const float area = range.bounds.halfArea();
        const float leafCost = config_.intersectionCost * blocksOf(count);
        auto leafWins = [&](float bestCost) {
            const float splitCost = bestCost < std::numeric_limits<float>::infinity() && area > 0
                                        ? config_.traversalCost + config_.intersectionCost * bestCost / area
                                        : std::numeric_limits<float>::infinity();
            return fitsLeaf && leafCost <= splitCost;
        };
        if (splitter_ && range.spare() > 0 && count >= minSpatialSplitRefs(config_)) {
            BuildBox overlap = object.left;
            overlap.intersect(object.right);
            const float overlapArea = overlap.halfArea();
            if (object.axis < 0 || (overlapArea > config_.spatialOverlap * rootHalfArea_ &&
                                    overlapArea > config_.spatialNodeOverlap * area)) {
                SpatialBinMapping mapping(range.bounds, config_.spatialBinCount);
                mapping.clipTriangles = count < kSpatialBoxClipMinRefs;
                mapping.splittableAxes = spatialAxesToBin(range, mapping, object.cost);
                SpatialSplit spatial;
                if (mapping.splittableAxes != 0) {
                    SpatialBins spatialBins(mapping.count);
                    binEvery(1, range, spatialBins, mapping, *splitter_);
                    spatial = spatialBins.bestSplit(mapping, blockShift());
                }
                const bool withinBudget = spatial.leftCount + spatial.rightCount - count <= range.spare();
                if (spatial.axis >= 0 && withinBudget && spatial.cost < object.cost) {
                    if (leafWins(spatial.cost)) return false;
                    splitSpatially(range, spatial, mapping, left, right);
                    return true;
                }
            }
        }
        if (leafWins(object.cost)) return false;
        if (object.axis >= 0 && count >= config_.parallelPartitionMinRefs) splitObjectsInParallel(range, object, left, right);
        else if (object.axis >= 0) splitObjects(range, object, left, right);
        else splitAtMedian(range, left, right);
        return true;
    }

    /// The sides of a plane a sample chose, over all references of the range: writes every
    /// reference's bins (for the partition) and sets the split's boxes, counts and cost to theirs.
    void measureObjectSplit(const BuildRange& range, const ObjectBinMapping& mapping, ObjectSplit& split) {
        struct Sides {
            BuildBox left, right;
            uint32_t leftCount = 0, rightCount = 0;
            void merge(const Sides& o) {
                left.grow(o.left);
                right.grow(o.right);
                leftCount += o.leftCount;
                rightCount += o.rightCount;
            }
        };
        Sides sides;
        reduceRange(
            range.begin, range.end, sides, [] { return Sides(); },
            [&](Sides& acc, uint32_t from, uint32_t to) {
                for (uint32_t i = from; i != to; ++i) {
                    BuildRef& ref = refs_[i];
                    const BuildBox box(ref);
                    ref.bins = ObjectBinMapping::packed(mapping.binOf(box.center2()));
                    if (ref.binAlong(split.axis) <= split.bin) acc.left.grow(box), ++acc.leftCount;
                    else acc.right.grow(box), ++acc.rightCount;
                }
            });
        split.left = sides.left;
        split.right = sides.right;
        split.leftCount = sides.leftCount;
        split.rightCount = sides.rightCount;
        split.cost = sides.left.halfArea() * blocksOf(sides.leftCount) + sides.right.halfArea() * blocksOf(sides.rightCount);
    }

    /// Bins every stride-th reference of the range (object or spatial bins; `args` follow the
    /// references, count and stride in Bins::add).
    template <class Bins, class... Args>
    void binEvery(uint32_t stride, const BuildRange& range, Bins& bins, const Args&... args) const {
        reduceRange(
            0, (range.size() + stride - 1) / stride, bins, [&] { return Bins(bins.count); },
            [&](Bins& acc, uint32_t from, uint32_t to) {
                acc.add(refs_.data() + range.begin + size_t(from) * stride, to - from, stride, args...);
            });
    }

    /// The axes along which to bin all references spatially (none: the object split wins). A sample
    /// is binned first, its counts scaled to the node's size: most spatial binnings find no split
    /// better than the object split (of the coffee maker's large nodes, 9 in 10), and where one may,
    /// the axes whose best split in the sample is far (kSpatialAxisSlack) behind the best axis's rarely
    /// win when all are binned. The sample's boxes err small, which favours binning all, but its counts
    /// are estimates either way, so a split that would have won can be missed (measured: see
    /// kSpatialSampleStride). Nodes too small to sample, and those without an object split (infinite
    /// cost), are binned along every axis.
    int spatialAxesToBin(const BuildRange& range, const SpatialBinMapping& mapping, float objectCost) const {
        if (range.size() < kSpatialSampleMinRefs || objectCost == std::numeric_limits<float>::infinity())
            return mapping.splittableAxes;
        SpatialBins sample(mapping.count);
        const uint32_t stride = std::max(kSpatialSampleStride, range.size() / kSpatialSampleMaxSize);
        binEvery(stride, range, sample, mapping, *splitter_);
        sample.scaleCounts(stride);
        const SpatialSplit best = sample.bestSplit(mapping, blockShift());
        int axes = 0;
        for (int a = 0; a < 3; ++a)
            if (best.axisCosts[a] < objectCost && best.axisCosts[a] <= best.cost * kSpatialAxisSlack) axes |= 1 << a;
        return axes;
    }

    /// In place, by the bins the binning left in the references. The children's boxes are the
    /// split's (the unions of their bins); their centroid bounds are gathered on the way.
    void splitObjects(const BuildRange& range, const ObjectSplit& split, BuildRange& left, BuildRange& right) {
        BuildRef* refs = refs_.data();
        BuildBox l, r;
        auto goesLeft = [&](const BuildRef& ref) { return ref.binAlong(split.axis) <= split.bin; };
        uint32_t i = range.begin, j = range.end;
        while (true) {
            while (i < j && goesLeft(refs[i])) l.grow(BuildBox(refs[i]).center2()), ++i;
            while (i < j && !goesLeft(refs[j - 1])) r.grow(BuildBox(refs[j - 1]).center2()), --j;
            if (i >= j) break;
            std::swap(refs[i], refs[j - 1]);
            l.grow(BuildBox(refs[i]).center2()), ++i;
            r.grow(BuildBox(refs[j - 1]).center2()), --j;
        }
        left = {range.begin, i, i, split.left, l};
        right = {i, range.end, range.end, split.right, r};
    }

    /// splitObjects on all threads, with the same result. Hoare's partition there swaps the k-th
    /// reference going right in [begin, mid) counted from the front with the k-th going left in
    /// [mid, end) counted from the back (mid = begin + the references going left); here blocks of
    /// references count them, chunks of the swaps find where they start, and then swap in parallel.
    /// (Centroid bounds merge per block: a NaN centroid, from a user primitive with empty bounds, makes
    /// min and max depend on order, so there they may differ from the serial scan's, though never
    /// with the thread count.)
    void splitObjectsInParallel(const BuildRange& range, const ObjectSplit& split, BuildRange& left,
                                BuildRange& right) {
        constexpr uint32_t kBlock = 4096, kSwapChunk = 4096;
        BuildRef* refs = refs_.data();
        auto goesLeft = [&](uint32_t i) { return refs[i].binAlong(split.axis) <= split.bin; };
        const uint32_t blocks = (range.size() + kBlock - 1) / kBlock;
        auto blockBegin = [&](uint32_t b) { return range.begin + b * kBlock; };
        auto blockEnd = [&](uint32_t b) { return std::min(range.end, range.begin + (b + 1) * kBlock); };

        struct Block {
            uint32_t lefts = 0;
            BuildBox leftCentroids, rightCentroids;
        };
        std::vector<Block> counted(blocks);
        tbb::parallel_for(uint32_t(0), blocks, [&](uint32_t b) {
            Block c;
            for (uint32_t i = blockBegin(b); i != blockEnd(b); ++i) {
                const __m128 centroid = BuildBox(refs[i]).center2();
                if (goesLeft(i)) ++c.lefts, c.leftCentroids.grow(centroid);
                else c.rightCentroids.grow(centroid);
            }
            counted[b] = c;
        });
        BuildBox leftCentroids, rightCentroids;
        uint32_t mid = range.begin;
        for (const Block& c : counted) {
            mid += c.lefts;
            leftCentroids.grow(c.leftCentroids);
            rightCentroids.grow(c.rightCentroids);
        }
        left = {range.begin, mid, mid, split.left, leftCentroids};
        right = {mid, range.end, range.end, split.right, rightCentroids};

        // Misplaced references of each block (going right before mid, going left from mid on) and
        // their ranks: rightRank[b] of the first in block b counted from the front, leftRank[b]
        // counted from the back.
        std::vector<uint32_t> rightRank(blocks + 1, 0), leftRank(blocks + 1, 0);
        for (uint32_t b = 0; b < blocks; ++b) {
            uint32_t wrongRight = 0;
            if (blockEnd(b) <= mid) wrongRight = blockEnd(b) - blockBegin(b) - counted[b].lefts;
            else
                for (uint32_t i = blockBegin(b); i < mid; ++i) wrongRight += !goesLeft(i);
            rightRank[b + 1] = rightRank[b] + wrongRight;
        }
        for (uint32_t b = blocks; b-- > 0;) {
            uint32_t wrongLeft = 0;
            if (blockBegin(b) >= mid) wrongLeft = counted[b].lefts;
            else
                for (uint32_t i = mid; i < blockEnd(b); ++i) wrongLeft += goesLeft(i);
            leftRank[b] = leftRank[b + 1] + wrongLeft;  // leftRank[b]: those in blocks b and after
        }
        const uint32_t misplaced = rightRank[blocks];
        assert(misplaced == leftRank[0]);

        // Where each chunk of swaps starts, found before any swap changes what the scans read.
        const uint32_t chunks = (misplaced + kSwapChunk - 1) / kSwapChunk;
        std::vector<std::pair<uint32_t, uint32_t>> starts(chunks);
        tbb::parallel_for(uint32_t(0), chunks, [&](uint32_t c) {
            const uint32_t k = c * kSwapChunk;
            // The block holding the k-th misplaced right reference, then the reference.
            uint32_t b = uint32_t(std::upper_bound(rightRank.begin(), rightRank.end(), k) - rightRank.begin()) - 1;
            uint32_t i = blockBegin(b);
            for (uint32_t seen = rightRank[b];; ++i)
                if (!goesLeft(i) && seen++ == k) break;
            // The k-th misplaced left reference from the back: leftRank falls with b.
            uint32_t d = blocks;
            while (leftRank[d] <= k) --d;  // blocks [d + 1, blocks) hold fewer than k + 1
            uint32_t j = blockEnd(d);
            for (uint32_t seen = leftRank[d + 1];; )
                if (goesLeft(--j) && seen++ == k) break;
            starts[c] = {i, j};
        });
        tbb::parallel_for(uint32_t(0), chunks, [&](uint32_t c) {
            auto [i, j] = starts[c];
            const uint32_t swaps = std::min(kSwapChunk, misplaced - c * kSwapChunk);
            for (uint32_t n = 0;; ++i) {
                if (goesLeft(i)) continue;
                while (!goesLeft(j)) --j;
                std::swap(refs[i], refs[j]);
                if (++n == swaps) break;
                --j;
            }
        });
    }

    void splitAtMedian(const BuildRange& range, BuildRange& left, BuildRange& right) {
        const int axis = range.centroids.bounds().largestAxis();
        const uint32_t mid = range.begin + range.size() / 2;
        BuildRef* refs = refs_.data();
        std::nth_element(refs + range.begin, refs + mid, refs + range.end, [axis](const BuildRef& a, const BuildRef& b) {
            const float ca = a.lower[axis] + a.upper[axis], cb = b.lower[axis] + b.upper[axis];
            return ca < cb || (ca == cb && a.prim < b.prim);
        });
        left = measured(range.begin, mid, mid);
        right = measured(mid, range.end, range.end);
    }

    /// References wholly below the plane go left, wholly above go right, and the ones across it are
    /// clipped into a part on each side (the duplicates take spare capacity), unless putting one
    /// whole on one side costs less (Stich et al.'s reference unsplitting). Where rounding leaves one
    /// side empty, the references are split at the median instead.
    void splitSpatially(const BuildRange& range, const SpatialSplit& split, const SpatialBinMapping& mapping,
                        BuildRange& left, BuildRange& right) {
        const float position = mapping.position(split.axis, split.bin + 1);
        auto binOf = [&](__m128 p) {
            alignas(16) int32_t bins[4];
            _mm_store_si128(reinterpret_cast<__m128i*>(bins), mapping.binOf(p));
            return bins[split.axis];
        };
        BuildRef* refs = refs_.data();
        BuildRef* first = refs + range.begin;
        BuildRef* end = refs + range.end;
        BuildRef* across = std::partition(first, end, [&](const BuildRef& r) { return binOf(BuildBox(r).upper) <= split.bin; });
        BuildRef* above = std::partition(across, end, [&](const BuildRef& r) { return binOf(BuildBox(r).lower) <= split.bin; });
        const uint32_t crossing = uint32_t(above - across);
        assert(range.end + crossing <= range.capacityEnd);
        // Make room after the crossing ones for their upper parts, then clip them.
        std::move_backward(above, end, end + crossing);
        BuildRef* lowerParts = across;
        BuildRef* upperParts = above;
        const float leftArea = split.left.halfArea(), rightArea = split.right.halfArea();
        const float leftCount = float(split.leftCount), rightCount = float(split.rightCount);
        const float splitCost = leftArea * leftCount + rightArea * rightCount;
        for (BuildRef* r = across; r != above; ++r) {
            const BuildRef ref = *r;
            BuildBox leftWhole = split.left, rightWhole = split.right;
            leftWhole.grow(BuildBox(ref));
            rightWhole.grow(BuildBox(ref));
            const float allLeft = leftWhole.halfArea() * leftCount + rightArea * (rightCount - 1);
            const float allRight = leftArea * (leftCount - 1) + rightWhole.halfArea() * rightCount;
            BuildBox below, over;
            if (allLeft < splitCost && allLeft <= allRight) below = BuildBox(ref);
            else if (allRight < splitCost) over = BuildBox(ref);
            else splitter_->triangle(ref.prim).split(BuildBox(ref), split.axis, position, below, over);
            if (below.empty() && over.empty()) below = BuildBox(ref);
            if (!below.empty()) below.storeInto(*lowerParts++ = ref);
            if (!over.empty()) over.storeInto(*upperParts++ = ref);
        }
        // Close the gaps the empty parts left: [first, lowerParts) go left, the upper parts and the
        // ones above follow.
        BuildRef* rightEnd = std::move(above + crossing, end + crossing, upperParts);
        rightEnd = std::move(above, rightEnd, lowerParts);
        const uint32_t mid = uint32_t(lowerParts - refs), stop = uint32_t(rightEnd - refs);
        if (mid == range.begin || mid == stop) {
            BuildRange whole = measured(range.begin, stop, range.capacityEnd);
            splitAtMedian(whole, left, right);
            return;
        }
        left = measured(range.begin, mid, mid);
        right = measured(mid, stop, stop);
    }

    /// Gives each child a share of the parent's spare capacity in proportion to its references: the
    /// right child's range moves up to make room after the left child's, by moving its first
    /// references into the free slots after its end (as Embree does: fewer moves than shifting all).
    void shareSpare(const BuildRange& parent, BuildRange& left, BuildRange& right) {
        const uint32_t spare = parent.capacityEnd - right.end;
        const uint32_t leftSpare = uint32_t(uint64_t(spare) * left.size() / (left.size() + right.size()));
        if (leftSpare > 0) {
            BuildRef* refs = refs_.data();
            const uint32_t moved = std::min(leftSpare, right.size());
            BuildRef* to = refs + right.end + leftSpare - moved;
            if (moved >= kParallelThreshold)
                tbb::parallel_for(tbb::blocked_range<uint32_t>(0, moved, kParallelGrain), [&](const tbb::blocked_range<uint32_t>& r) {
                    std::copy(refs + right.begin + r.begin(), refs + right.begin + r.end(), to + r.begin());
                });
            else
                std::copy(refs + right.begin, refs + right.begin + moved, to);
            right.begin += leftSpare;
            right.end += leftSpare;
        }
        left.capacityEnd = right.begin;
        right.capacityEnd = parent.capacityEnd;
    }

    /// primIndices from the subtree's leaves in depth-first order from `offset` on, so that every
    /// subtree's primitives are contiguous (spatial splits leave unused capacity between the ranges).
    void gatherLeaves(uint32_t nodeIndex, uint32_t offset) {
        BinaryNode& node = nodes_[nodeIndex];
        if (node.isLeaf()) {
            for (uint32_t i = 0; i != node.count; ++i) out_.primIndices[offset + i] = refs_[node.first + i].prim;
            node.first = offset;
            return;
        }
        const uint32_t left = node.first, rightOffset = offset + refsBelow_[left];
        if (refsBelow_[nodeIndex] >= kParallelThreshold)
            tbb::parallel_invoke([&] { gatherLeaves(left, offset); }, [&] { gatherLeaves(left + 1, rightOffset); });
        else {
            gatherLeaves(left, offset);
            gatherLeaves(left + 1, rightOffset);
        }
    }

    BuildRefs& refs_;
    const BvhBuildConfig& config_;
    const TriangleSplitter* splitter_;
    BinaryBvh& out_;
    BinaryNode* nodes_ = nullptr;
    UninitializedVector<uint32_t> refsBelow_;  ///< per node: the references in its subtree's leaves
    float rootHalfArea_ = 0;
    const bool toSinglePrims_;  ///< split down to single primitives (BvhBuildConfig::singlePrimLeavesBelow)
    /// Taken by every inner node on every thread: on a cache line of its own, so that its writes do
    /// not evict the members above from the other threads' caches.
    alignas(64) std::atomic<uint32_t> nodeCount_{0};
};

} // namespace

size_t buildRefCapacity(size_t primCount, const BvhBuildConfig& config) {
    if (config.quality != BuildQuality::High) return primCount;
    return primCount + size_t(double(primCount) * std::max(0.0f, config.replicationBudget));
}

size_t minSpatialSplitRefs(const BvhBuildConfig& config) {
    if (config.quality != BuildQuality::High) return std::numeric_limits<size_t>::max();
    return size_t(std::max(config.spatialMinRefs, 2));  // one reference is a leaf
}

BinaryBvh buildBinaryBvh(BuildRefs refs, const BvhBuildConfig& config, const TriangleSplitter* splitter) {
    assert(!refs.empty());
    assert(config.binCount >= 2 && config.binCount <= kMaxObjectBins);
    assert(config.spatialBinCount >= 2 && config.spatialBinCount <= kMaxSpatialBins);
    assert(config.blockSize > 0 && (config.blockSize & (config.blockSize - 1)) == 0);
    BinaryBvh bvh;
    Builder(refs, config, splitter, bvh).build();
    return bvh;
}

} // namespace wideray
