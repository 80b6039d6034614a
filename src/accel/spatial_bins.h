#pragma once
// Spatial splits (Stich, Friedrich and Dietrich 2009, "Spatial Splits in Bounding Volume
// Hierarchies"): the node's box is cut into bins of equal width along each axis, every reference is
// clipped into each bin it overlaps, and a sweep finds the plane of least SAH cost counting the
// references that straddle it on both sides.
#include <algorithm>

#include "accel/object_bins.h"
#include "accel/triangle_splitter.h"

namespace wideray {

constexpr int kMaxSpatialBins = 32;

/// Bins of equal width over the node's box: bin = (x - offset) * scale, clamped; bin b's lower plane
/// is position(axis, b).
struct SpatialBinMapping {
    int count = 0;
    __m128 offset, scale;
    int splittableAxes = 0;  ///< bit a: binned along axis a (the box has extent there, and the builder wants it)
    bool clipTriangles = true;  ///< false: a reference's parts in its bins are its box cut by the planes
    float planes[3][kMaxSpatialBins + 1];  ///< [axis][bin]: the bin's lower plane

    SpatialBinMapping(const BuildBox& bounds, int binCount) : count(binCount) {
        offset = bounds.lower;
        const __m128 extent = _mm_sub_ps(bounds.upper, bounds.lower);
        const __m128 spread = _mm_cmpgt_ps(extent, _mm_setzero_ps());
        scale = _mm_and_ps(spread, _mm_div_ps(_mm_set1_ps(float(count)), extent));
        const __m128 width = _mm_mul_ps(extent, _mm_set1_ps(1.0f / float(count)));
        splittableAxes = _mm_movemask_ps(spread) & 7;
        for (int a = 0; a < 3; ++a)
            for (int b = 0; b <= count; ++b)
                planes[a][b] = BuildBox::lane(offset, a) + float(b) * BuildBox::lane(width, a);
    }

    __m128i binOf(__m128 p) const {
        const __m128i bin = _mm_cvttps_epi32(_mm_mul_ps(_mm_sub_ps(p, offset), scale));
        return _mm_min_epi32(_mm_max_epi32(bin, _mm_setzero_si128()), _mm_set1_epi32(count - 1));
    }

    float position(int axis, int bin) const { return planes[axis][bin]; }
};

/// The best spatial split: the plane between bins `bin` and `bin + 1` along `axis`.
/// leftCount + rightCount exceeds the node's count by the duplicates.
struct SpatialSplit : BestPlane {
    BuildBox left, right;  ///< the boxes of the two sides' (clipped) references
};

struct SpatialBins {
    AxisBinBoxes<kMaxSpatialBins> boxes;
    alignas(16) uint32_t enter[kMaxSpatialBins][4];  ///< [bin][axis]: references starting there
    alignas(16) uint32_t exit[kMaxSpatialBins][4];   ///< [bin][axis]: references ending there
    int count;

    explicit SpatialBins(int binCount) : count(binCount) {
        boxes.clear(count);
        for (int b = 0; b < count; ++b) {
            _mm_store_si128(reinterpret_cast<__m128i*>(enter[b]), _mm_setzero_si128());
            _mm_store_si128(reinterpret_cast<__m128i*>(exit[b]), _mm_setzero_si128());
        }
    }

    BuildBox box(int axis, int bin) const { return boxes.box(axis, bin); }

    /// Bins refs[0], refs[stride], refs[2 * stride], ... (refCount of them).
    void add(const BuildRef* refs, size_t refCount, size_t stride, const SpatialBinMapping& mapping,
             const TriangleSplitter& splitter) {
        addInterleaved(*this, refCount, [&](SpatialBins& bins, size_t i) { bins.add(refs[i * stride], mapping, splitter); });
    }

    /// Counts the reference where it starts and ends along each axis, and grows each bin it overlaps
    /// along the mapping's splittable axes by the part of its triangle inside. The sweep ignores the
    /// other axes: those the node's box is flat along, and those the builder chose not to bin.
    void add(const BuildRef& ref, const SpatialBinMapping& mapping, const TriangleSplitter& splitter) {
        const BuildBox box(ref);
        const __m128i firstBins = mapping.binOf(box.lower), lastBins = mapping.binOf(box.upper);
        alignas(16) int32_t first[4], last[4];
        _mm_store_si128(reinterpret_cast<__m128i*>(first), firstBins);
        _mm_store_si128(reinterpret_cast<__m128i*>(last), lastBins);
        for (int a = 0; a < 3; ++a) {
            ++enter[first[a]][a];
            ++exit[last[a]][a];
        }
        const int axes = mapping.splittableAxes;
        if (((_mm_movemask_ps(_mm_castsi128_ps(_mm_cmpeq_epi32(firstBins, lastBins))) | ~axes) & 7) == 7) {
            for (int a = 0; a < 3; ++a)
                if (axes >> a & 1) boxes.grow(a, first[a], box);  // inside one bin: nothing to clip
            return;
        }
        if (!mapping.clipTriangles) {
            for (int a = 0; a < 3; ++a) {
                if (!(axes >> a & 1)) continue;
                const __m128 onAxis = BuildBox::axisMask(a);
                for (int b = first[a]; b <= last[a]; ++b) {
                    BuildBox part = box;
                    if (b > first[a]) part.lower = _mm_blendv_ps(part.lower, _mm_set1_ps(mapping.position(a, b)), onAxis);
                    if (b < last[a]) part.upper = _mm_blendv_ps(part.upper, _mm_set1_ps(mapping.position(a, b + 1)), onAxis);
                    boxes.grow(a, b, part);
                }
            }
            return;
        }
        const SplitTriangle triangle = splitter.triangle(ref.prim);
        for (int a = 0; a < 3; ++a) {
            if (!(axes >> a & 1)) continue;
            BuildBox rest = box;
            for (int b = first[a]; b < last[a]; ++b) {
                BuildBox left, right;
                triangle.split(rest, a, mapping.position(a, b + 1), left, right);
                boxes.grow(a, b, left);
                rest = right;
            }
            boxes.grow(a, last[a], rest);
        }
    }

    void merge(const SpatialBins& other) {
        boxes.merge(other.boxes, count);
        for (int b = 0; b < count; ++b)
            for (int a = 0; a < 3; ++a) {
                enter[b][a] += other.enter[b][a];
                exit[b][a] += other.exit[b][a];
            }
    }

    /// Counts each reference `factor` times: a sample's bins, scaled to the node's size.
    void scaleCounts(uint32_t factor) {
        for (int b = 0; b < count; ++b)
            for (int a = 0; a < 3; ++a) {
                enter[b][a] *= factor;
                exit[b][a] *= factor;
            }
    }

    SpatialSplit bestSplit(const SpatialBinMapping& mapping, uint32_t blockShift) const {
        const BestPlane plane = sweepPlanes(
            boxes, count, mapping.splittableAxes, blockShift,
            [&](int b) { return _mm_load_si128(reinterpret_cast<const __m128i*>(enter[b])); },
            [&](int b) { return _mm_load_si128(reinterpret_cast<const __m128i*>(exit[b])); });
        SpatialSplit best{plane, {}, {}};
        if (best.axis >= 0) boxes.sides(best.axis, best.bin, count, best.left, best.right);
        return best;
    }
};

} // namespace wideray
