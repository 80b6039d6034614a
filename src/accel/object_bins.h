#pragma once
// Binned SAH over object splits (Wald 2007, "On fast construction of SAH-based bounding volume
// hierarchies"): references are binned by centroid along all three axes at once, and a sweep over the
// bins finds the split plane of least SAH cost.
#include <algorithm>
#include <array>

#include "accel/build_ref.h"

namespace wideray {

constexpr int kMaxObjectBins = 64;
constexpr size_t kInterleaveThreshold = 256;

/// The SAH cost of `count` primitives in a box of half area `halfArea`, intersected in blocks.
inline float sideCost(float halfArea, uint32_t count, uint32_t blockSize) {
    return halfArea * float((count + blockSize - 1) / blockSize);
}

/// Sweeps the planes between the bins along one axis: visit(bin, cost, left, right) for each plane
/// after `bin` with references on both sides, left and right their counts (leftAdd(b), rightAdd(b):
/// what bin b adds to each side), cost the SAH cost of both sides.
template <int MaxBins, class LeftAdd, class RightAdd, class Visit>
void sweepPlanes(const AxisBinBoxes<MaxBins>& boxes, int axis, int bins, uint32_t blockSize, LeftAdd leftAdd,
                 RightAdd rightAdd, Visit visit) {
    std::array<float, MaxBins> rightCost;
    std::array<uint32_t, MaxBins> rightCount;
    BuildBox acc;
    uint32_t n = 0;
    for (int b = bins - 1; b > 0; --b) {
        acc.grow(boxes.box(axis, b));
        n += rightAdd(b);
        rightCount[b] = n;
        rightCost[b] = sideCost(acc.halfArea(), n, blockSize);
    }
    acc = BuildBox();
    n = 0;
    for (int b = 0; b < bins - 1; ++b) {
        acc.grow(boxes.box(axis, b));
        n += leftAdd(b);
        if (n == 0 || rightCount[b + 1] == 0) continue;
        visit(b, sideCost(acc.halfArea(), n, blockSize) + rightCost[b + 1], n, rightCount[b + 1]);
    }
}

/// How centroids map to bins along each axis: bin = (center2 - offset) * scale, clamped. Fewer bins
/// for fewer references (as Embree does): small nodes cost a short sweep, not a long one.
struct ObjectBinMapping {
    int count = 0;
    __m128 offset, scale;
    int splittableAxes = 0;  ///< bit a: the centroids spread along axis a

    ObjectBinMapping(const BuildBox& centroids, uint32_t refCount, int maxBins) {
        count = std::clamp(int(4.0f + 0.05f * float(refCount)), 2, maxBins);
        offset = centroids.lower;
        const __m128 extent = _mm_sub_ps(centroids.upper, centroids.lower);
        const __m128 spread = _mm_cmpgt_ps(extent, _mm_setzero_ps());
        // The 0.99999 keeps the largest centroid inside the last bin despite rounding.
        scale = _mm_and_ps(spread, _mm_div_ps(_mm_set1_ps(0.99999f * float(count)), extent));
        splittableAxes = _mm_movemask_ps(spread) & 7;
    }

    bool splittable(int axis) const { return splittableAxes >> axis & 1; }

    __m128i binOf(__m128 center2) const {
        const __m128i bin = _mm_cvttps_epi32(_mm_mul_ps(_mm_sub_ps(center2, offset), scale));
        return _mm_min_epi32(_mm_max_epi32(bin, _mm_setzero_si128()), _mm_set1_epi32(count - 1));
    }

    int binOf(const BuildRef& ref, int axis) const {
        alignas(16) int32_t bins[4];
        _mm_store_si128(reinterpret_cast<__m128i*>(bins), binOf(BuildBox(ref).center2()));
        return bins[axis];
    }
};

/// The best object split: references whose centroid bin along `axis` is <= `bin` go left.
struct ObjectSplit {
    int axis = -1;
    int bin = 0;
    float cost = std::numeric_limits<float>::infinity();  ///< sum of both sides' sideCost
    BuildBox left, right;
};

struct ObjectBins {
    AxisBinBoxes<kMaxObjectBins> boxes;
    alignas(16) uint32_t counts[kMaxObjectBins][4];  ///< counts[bin][axis]
    int count;

    explicit ObjectBins(int binCount) : count(binCount) {
        boxes.clear(count);
        for (int b = 0; b < count; ++b) _mm_store_si128(reinterpret_cast<__m128i*>(counts[b]), _mm_setzero_si128());
    }

    BuildBox box(int axis, int bin) const { return boxes.box(axis, bin); }

    void add(const BuildRef* refs, size_t refCount, const ObjectBinMapping& mapping) {
        if (refCount < kInterleaveThreshold) {
            addEvery(refs, refCount, 1, mapping);
            return;
        }
        // Neighbouring references mostly fall in the same bins (partitions keep them spatially
        // sorted), which chains each bin update to the previous one through memory: odd and even
        // references go to two bin sets, merged at the end.
        ObjectBins odd(count);
        addEvery(refs, refCount, 2, mapping);
        odd.addEvery(refs + 1, refCount - 1, 2, mapping);
        merge(odd);
    }

    /// Bins refs[0], refs[stride], ... (fewer than refCount).
    void addEvery(const BuildRef* refs, size_t refCount, size_t stride, const ObjectBinMapping& mapping) {
        for (size_t i = 0; i < refCount; i += stride) {
            const BuildBox box(refs[i]);
            alignas(16) int32_t bins[4];
            _mm_store_si128(reinterpret_cast<__m128i*>(bins), mapping.binOf(box.center2()));
            for (int a = 0; a < 3; ++a) {
                boxes.grow(a, bins[a], box);
                ++counts[bins[a]][a];
            }
        }
    }

    void merge(const ObjectBins& other) {
        boxes.merge(other.boxes, count);
        for (int b = 0; b < count; ++b)
            for (int a = 0; a < 3; ++a) counts[b][a] += other.counts[b][a];
    }

    ObjectSplit bestSplit(const ObjectBinMapping& mapping, uint32_t blockSize) const {
        ObjectSplit best;
        for (int a = 0; a < 3; ++a) {
            if (!mapping.splittable(a)) continue;
            auto binCount = [&](int b) { return counts[b][a]; };
            sweepPlanes(boxes, a, count, blockSize, binCount, binCount, [&](int b, float cost, uint32_t, uint32_t) {
                if (cost < best.cost) best = {a, b, cost, {}, {}};
            });
        }
        if (best.axis >= 0) boxes.sides(best.axis, best.bin, count, best.left, best.right);
        return best;
    }
};

} // namespace wideray
