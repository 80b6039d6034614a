#pragma once
// Binned SAH over object splits (Wald 2007, "On fast construction of SAH-based bounding volume
// hierarchies"): references are binned by centroid along all three axes at once, and a sweep over the
// bins finds the split plane of least SAH cost.
#include <algorithm>
#include <limits>

#include "accel/build_ref.h"

namespace wideray {

constexpr int kMaxObjectBins = 64;
constexpr size_t kInterleaveThreshold = 256;

/// Calls add(bins, i) for i in [0, refCount). Neighbouring references mostly fall in the same bins
/// (partitions keep them spatially sorted), which chains each bin update to the previous one through
/// memory: above kInterleaveThreshold, odd and even references go to two bin sets, merged at the end.
template <class Bins, class Add>
[[gnu::always_inline]] inline void addInterleaved(Bins& bins, size_t refCount, Add add) {
    if (refCount < kInterleaveThreshold) {
        for (size_t i = 0; i < refCount; ++i) add(bins, i);
        return;
    }
    Bins odd(bins.count);
    size_t i = 0;
    for (; i + 1 < refCount; i += 2) {
        add(bins, i);
        add(odd, i + 1);
    }
    if (i < refCount) add(bins, i);
    bins.merge(odd);
}

/// The plane of least SAH cost that sweepPlanes found (axis -1: none with references on both sides).
struct BestPlane {
    int axis = -1;
    int bin = 0;  ///< the plane is after this bin
    float cost = std::numeric_limits<float>::infinity();  ///< the sum of both sides' SAH costs
    uint32_t leftCount = 0, rightCount = 0;
    /// The best plane's cost along each axis (cost is the least of them).
    float axisCosts[3] = {std::numeric_limits<float>::infinity(), std::numeric_limits<float>::infinity(),
                          std::numeric_limits<float>::infinity()};
};

/// The SAH costs of three boxes (the three axes' sides, in lanes x, y, z) holding `counts` primitives,
/// intersected in blocks of 1 << blockShift: half area times blocks, as BuildBox::halfArea adds it.
inline __m128 sideCosts(const BuildBox (&sides)[3], __m128i counts, uint32_t blockShift) {
    __m128 x = _mm_sub_ps(sides[0].upper, sides[0].lower), y = _mm_sub_ps(sides[1].upper, sides[1].lower),
           z = _mm_sub_ps(sides[2].upper, sides[2].lower), w = _mm_setzero_ps();
    _MM_TRANSPOSE4_PS(x, y, z, w);  // x: the three boxes' extents along x, and so on
    const __m128 area = _mm_add_ps(_mm_add_ps(_mm_mul_ps(x, y), _mm_mul_ps(y, z)), _mm_mul_ps(z, x));
    const __m128 zero = _mm_setzero_ps();
    const __m128 empty = _mm_or_ps(_mm_or_ps(_mm_cmplt_ps(x, zero), _mm_cmplt_ps(y, zero)), _mm_cmplt_ps(z, zero));
    const __m128i blocks =
        _mm_srl_epi32(_mm_add_epi32(counts, _mm_set1_epi32((1 << blockShift) - 1)), _mm_cvtsi32_si128(int(blockShift)));
    return _mm_mul_ps(_mm_andnot_ps(empty, area), _mm_cvtepi32_ps(blocks));
}

/// Sweeps the planes between the bins along the axes in `axes` (bit a: axis a), all three at once in
/// the lanes of SSE registers. leftAdd(b) and rightAdd(b) return per axis (__m128i lanes x, y, z) what
/// bin b adds to the count of the side it is on. Among the planes with references on both sides, the
/// one of least cost wins; ties go to the lower axis, then to the lower bin.
template <int MaxBins, class LeftAdd, class RightAdd>
BestPlane sweepPlanes(const AxisBinBoxes<MaxBins>& boxes, int bins, int axes, uint32_t blockShift, LeftAdd leftAdd,
                      RightAdd rightAdd) {
    __m128 rightCost[MaxBins];
    __m128i rightCount[MaxBins];
    BuildBox sides[3];
    __m128i n = _mm_setzero_si128();
    for (int b = bins - 1; b > 0; --b) {
        for (int a = 0; a < 3; ++a) sides[a].grow(boxes.box(a, b));
        n = _mm_add_epi32(n, rightAdd(b));
        rightCount[b] = n;
        rightCost[b] = sideCosts(sides, n, blockShift);
    }
    for (BuildBox& side : sides) side = BuildBox();
    n = _mm_setzero_si128();
    const __m128i zero = _mm_setzero_si128();
    const __m128i axisLanes = _mm_cmpgt_epi32(_mm_and_si128(_mm_set1_epi32(axes), _mm_setr_epi32(1, 2, 4, 8)), zero);
    __m128 bestCost = _mm_set1_ps(std::numeric_limits<float>::infinity());
    __m128i bestBin = _mm_set1_epi32(-1), bestLeft = zero, bestRight = zero;
    for (int b = 0; b < bins - 1; ++b) {
        for (int a = 0; a < 3; ++a) sides[a].grow(boxes.box(a, b));
        n = _mm_add_epi32(n, leftAdd(b));
        const __m128 cost = _mm_add_ps(sideCosts(sides, n, blockShift), rightCost[b + 1]);
        const __m128i bothSides = _mm_andnot_si128(
            _mm_or_si128(_mm_cmpeq_epi32(n, zero), _mm_cmpeq_epi32(rightCount[b + 1], zero)), axisLanes);
        const __m128i better = _mm_and_si128(bothSides, _mm_castps_si128(_mm_cmplt_ps(cost, bestCost)));
        bestCost = _mm_blendv_ps(bestCost, cost, _mm_castsi128_ps(better));
        bestBin = _mm_blendv_epi8(bestBin, _mm_set1_epi32(b), better);
        bestLeft = _mm_blendv_epi8(bestLeft, n, better);
        bestRight = _mm_blendv_epi8(bestRight, rightCount[b + 1], better);
    }
    alignas(16) float costs[4];
    alignas(16) int32_t bin[4];
    alignas(16) uint32_t left[4], right[4];
    _mm_store_ps(costs, bestCost);
    _mm_store_si128(reinterpret_cast<__m128i*>(bin), bestBin);
    _mm_store_si128(reinterpret_cast<__m128i*>(left), bestLeft);
    _mm_store_si128(reinterpret_cast<__m128i*>(right), bestRight);
    BestPlane best;
    for (int a = 0; a < 3; ++a) {
        if (bin[a] < 0) continue;
        best.axisCosts[a] = costs[a];
        if (costs[a] < best.cost) {
            best.axis = a;
            best.bin = bin[a];
            best.cost = costs[a];
            best.leftCount = left[a];
            best.rightCount = right[a];
        }
    }
    return best;
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

    __m128i binOf(__m128 center2) const {
        const __m128i bin = _mm_cvttps_epi32(_mm_mul_ps(_mm_sub_ps(center2, offset), scale));
        return _mm_min_epi32(_mm_max_epi32(bin, _mm_setzero_si128()), _mm_set1_epi32(count - 1));
    }

    /// Bins of up to 255 in the low bytes: x, y, z (and the fourth lane's).
    static uint32_t packed(__m128i bins) {
        const __m128i words = _mm_packus_epi32(bins, bins);
        return uint32_t(_mm_cvtsi128_si32(_mm_packus_epi16(words, words)));
    }
};

/// The best object split: references whose centroid bin along `axis` is <= `bin` go left.
struct ObjectSplit : BestPlane {
    BuildBox left, right;  ///< the boxes of the two sides' references
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

    /// Bins refs[0], refs[stride], refs[2 * stride], ... (refCount of them) and writes each one's bins
    /// into it (BuildRef::bins).
    void add(BuildRef* refs, size_t refCount, size_t stride, const ObjectBinMapping& mapping) {
        addInterleaved(*this, refCount, [&](ObjectBins& bins, size_t i) { bins.add(refs[i * stride], mapping); });
    }

    void add(BuildRef& ref, const ObjectBinMapping& mapping) {
        const BuildBox box(ref);
        const __m128i bin = mapping.binOf(box.center2());
        ref.bins = ObjectBinMapping::packed(bin);
        alignas(16) int32_t bins[4];
        _mm_store_si128(reinterpret_cast<__m128i*>(bins), bin);
        for (int a = 0; a < 3; ++a) {
            boxes.grow(a, bins[a], box);
            ++counts[bins[a]][a];
        }
    }

    void merge(const ObjectBins& other) {
        boxes.merge(other.boxes, count);
        for (int b = 0; b < count; ++b)
            for (int a = 0; a < 3; ++a) counts[b][a] += other.counts[b][a];
    }

    /// Counts each reference `factor` times: a sample's bins, scaled to the node's size.
    void scaleCounts(uint32_t factor) {
        for (int b = 0; b < count; ++b)
            for (int a = 0; a < 3; ++a) counts[b][a] *= factor;
    }

    ObjectSplit bestSplit(const ObjectBinMapping& mapping, uint32_t blockShift) const {
        auto binCounts = [&](int b) { return _mm_load_si128(reinterpret_cast<const __m128i*>(counts[b])); };
        const BestPlane plane = sweepPlanes(boxes, count, mapping.splittableAxes, blockShift, binCounts, binCounts);
        ObjectSplit best{plane, {}, {}};
        if (best.axis >= 0) boxes.sides(best.axis, best.bin, count, best.left, best.right);
        return best;
    }
};

} // namespace wideray
