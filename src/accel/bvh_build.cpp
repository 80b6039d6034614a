#include "accel/bvh_binary.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cassert>

#include <tbb/parallel_invoke.h>
#include <tbb/parallel_reduce.h>
#include <tbb/blocked_range.h>

namespace wideray {
namespace {

constexpr int kMaxBins = 64;
constexpr int kMedianDepth = kMaxBvhDepth - 24;  // leaves room for log2(2^24) median levels
constexpr size_t kParallelThreshold = 4096;

struct Bin {
    Bounds3f bounds;
    uint32_t count = 0;
};

/// The bins of the three axes; only the first binCount of each are in use (and initialized).
struct BinSet {
    int binCount;
    std::array<std::array<Bin, kMaxBins>, 3> bins;

    explicit BinSet(int count) : binCount(count) {
        for (auto& axis : bins)
            for (int b = 0; b < binCount; ++b) axis[b] = Bin{};
    }
    void merge(const BinSet& other) {
        for (int a = 0; a < 3; ++a)
            for (int b = 0; b < binCount; ++b) {
                bins[a][b].bounds.grow(other.bins[a][b].bounds);
                bins[a][b].count += other.bins[a][b].count;
            }
    }
};

/// How centers map to bins along one axis: bin = (center - lower) * scale, clamped.
struct AxisBins {
    float lower = 0, scale = 0;
    bool splittable = false;  ///< the centers spread along the axis
};

struct Split {
    int axis = -1;
    int bin = 0;  ///< primitives in bins [0, bin] go left
    float cost = std::numeric_limits<float>::infinity();
};

class Builder {
public:
    Builder(std::span<const Bounds3f> bounds, std::span<const glm::vec3> centers, const BvhBuildConfig& config,
            BinaryBvh& out)
        : bounds_(bounds), centers_(centers), config_(config), out_(out) {}

    void build() {
        size_t n = bounds_.size();
        out_.primIndices.resize(n);
        for (size_t i = 0; i < n; ++i) out_.primIndices[i] = uint32_t(i);
        out_.nodes.resize(2 * n - 1);
        nodeCount_ = 1;
        buildNode(0, 0, uint32_t(n), 0);
        out_.nodes.resize(nodeCount_);
    }

private:
    float blocks(uint32_t count) const {
        return float((count + uint32_t(config_.blockSize) - 1) / uint32_t(config_.blockSize));
    }

    void rangeBounds(uint32_t begin, uint32_t end, Bounds3f& nodeBounds, Bounds3f& centerBounds) const {
        auto reduce = [&](const tbb::blocked_range<uint32_t>& r, std::pair<Bounds3f, Bounds3f> acc) {
            for (uint32_t i = r.begin(); i != r.end(); ++i) {
                uint32_t p = out_.primIndices[i];
                acc.first.grow(bounds_[p]);
                acc.second.grow(centers_[p]);
            }
            return acc;
        };
        auto join = [](std::pair<Bounds3f, Bounds3f> a, const std::pair<Bounds3f, Bounds3f>& b) {
            a.first.grow(b.first);
            a.second.grow(b.second);
            return a;
        };
        std::pair<Bounds3f, Bounds3f> result;
        if (end - begin >= kParallelThreshold)
            result = tbb::parallel_reduce(tbb::blocked_range<uint32_t>(begin, end, 1024), result, reduce, join);
        else
            result = reduce(tbb::blocked_range<uint32_t>(begin, end), result);
        nodeBounds = result.first;
        centerBounds = result.second;
    }

    AxisBins axisBins(const Bounds3f& centerBounds, int axis) const {
        AxisBins bins;
        bins.lower = centerBounds.lower[axis];
        bins.splittable = centerBounds.upper[axis] > centerBounds.lower[axis];
        bins.scale = float(config_.binCount) / (centerBounds.upper[axis] - bins.lower);
        return bins;
    }

    int binOf(const glm::vec3& center, int axis, const AxisBins& bins) const {
        int b = int((center[axis] - bins.lower) * bins.scale);
        return std::clamp(b, 0, config_.binCount - 1);
    }

    void fillBins(uint32_t begin, uint32_t end, const std::array<AxisBins, 3>& axes, BinSet& set) const {
        for (uint32_t i = begin; i != end; ++i) {
            const uint32_t p = out_.primIndices[i];
            for (int a = 0; a < 3; ++a) {
                if (!axes[a].splittable) continue;
                Bin& bin = set.bins[a][binOf(centers_[p], a, axes[a])];
                bin.bounds.grow(bounds_[p]);
                ++bin.count;
            }
        }
    }

    Split findSahSplit(uint32_t begin, uint32_t end, const Bounds3f& centerBounds) const {
        const int binCount = config_.binCount;
        const std::array<AxisBins, 3> axes = {axisBins(centerBounds, 0), axisBins(centerBounds, 1),
                                              axisBins(centerBounds, 2)};
        BinSet binSet(binCount);
        if (end - begin >= kParallelThreshold)
            binSet = tbb::parallel_reduce(
                tbb::blocked_range<uint32_t>(begin, end, 4096), BinSet(binCount),
                [&](const tbb::blocked_range<uint32_t>& r, BinSet acc) {
                    fillBins(r.begin(), r.end(), axes, acc);
                    return acc;
                },
                [](BinSet a, const BinSet& b) { a.merge(b); return a; });
        else
            fillBins(begin, end, axes, binSet);

        Split best;
        for (int a = 0; a < 3; ++a) {
            if (!axes[a].splittable) continue;
            const auto& bins = binSet.bins[a];
            std::array<float, kMaxBins> rightCost{};
            Bounds3f acc;
            uint32_t count = 0;
            for (int b = binCount - 1; b > 0; --b) {
                acc.grow(bins[b].bounds);
                count += bins[b].count;
                rightCost[b] = acc.area() * blocks(count);
            }
            acc = Bounds3f();
            count = 0;
            for (int b = 0; b < binCount - 1; ++b) {
                acc.grow(bins[b].bounds);
                count += bins[b].count;
                float cost = acc.area() * blocks(count) + rightCost[b + 1];
                if (count > 0 && count < end - begin && cost < best.cost) best = {a, b, cost};
            }
        }
        return best;
    }

    uint32_t partitionAtBin(uint32_t begin, uint32_t end, const Split& split, const Bounds3f& centerBounds) {
        auto first = out_.primIndices.begin();
        const AxisBins bins = axisBins(centerBounds, split.axis);
        auto mid = std::partition(first + begin, first + end, [&](uint32_t p) {
            return binOf(centers_[p], split.axis, bins) <= split.bin;
        });
        return uint32_t(mid - first);
    }

    uint32_t partitionAtMedian(uint32_t begin, uint32_t end, const Bounds3f& centerBounds) {
        int axis = centerBounds.largestAxis();
        uint32_t mid = begin + (end - begin) / 2;
        auto first = out_.primIndices.begin();
        std::nth_element(first + begin, first + mid, first + end, [&](uint32_t a, uint32_t b) {
            float ca = centers_[a][axis], cb = centers_[b][axis];
            return ca < cb || (ca == cb && a < b);
        });
        return mid;
    }

    void buildNode(uint32_t nodeIndex, uint32_t begin, uint32_t end, int depth) {
        Bounds3f nodeBounds, centerBounds;
        rangeBounds(begin, end, nodeBounds, centerBounds);
        BinaryNode& node = out_.nodes[nodeIndex];
        node.bounds = nodeBounds;
        uint32_t count = end - begin;

        uint32_t mid = begin;
        if (count == 1) {
            mid = begin;
        } else if (config_.split == SplitMethod::Median || depth >= kMedianDepth) {
            mid = count <= uint32_t(config_.maxLeafSize) ? begin : partitionAtMedian(begin, end, centerBounds);
        } else {
            Split split = findSahSplit(begin, end, centerBounds);
            float leafCost = config_.intersectionCost * blocks(count);
            float splitCost = split.axis < 0 ? std::numeric_limits<float>::infinity()
                                             : config_.traversalCost +
                                                   config_.intersectionCost * split.cost / nodeBounds.area();
            bool makeLeaf = count <= uint32_t(config_.maxLeafSize) && leafCost <= splitCost;
            if (!makeLeaf)
                mid = split.axis >= 0 ? partitionAtBin(begin, end, split, centerBounds)
                                      : partitionAtMedian(begin, end, centerBounds);
        }

        if (mid == begin || mid == end) {
            node.first = begin;
            node.count = count;
            return;
        }
        uint32_t left = nodeCount_.fetch_add(2);
        node.first = left;
        node.count = 0;
        if (count >= kParallelThreshold)
            tbb::parallel_invoke([&] { buildNode(left, begin, mid, depth + 1); },
                                 [&] { buildNode(left + 1, mid, end, depth + 1); });
        else {
            buildNode(left, begin, mid, depth + 1);
            buildNode(left + 1, mid, end, depth + 1);
        }
    }

    std::span<const Bounds3f> bounds_;
    std::span<const glm::vec3> centers_;
    const BvhBuildConfig& config_;
    BinaryBvh& out_;
    std::atomic<uint32_t> nodeCount_{0};
};

} // namespace

BinaryBvh buildBinaryBvh(std::span<const Bounds3f> primBounds, std::span<const glm::vec3> centers,
                         const BvhBuildConfig& config) {
    assert(primBounds.size() == centers.size() && !primBounds.empty());
    assert(config.binCount >= 2 && config.binCount <= kMaxBins);
    BinaryBvh bvh;
    Builder(primBounds, centers, config, bvh).build();
    return bvh;
}

} // namespace wideray
