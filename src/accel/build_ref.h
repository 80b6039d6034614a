#pragma once
// What the BVH builders sort: one reference per primitive (more than one where spatial splits clip
// it), 32 bytes, its box loaded as two SSE registers. The builders' arithmetic is on BuildBox.
#include <nmmintrin.h>  // SSE4.2, and SSE4.1's blends

#include <cstdint>
#include <limits>

#include "core/bounds.h"
#include "core/default_init_allocator.h"

namespace wideray {

struct alignas(16) BuildRef {
    glm::vec3 lower;
    uint32_t prim;  ///< the primitive's index in the builder's input
    glm::vec3 upper;
    /// The reference's object bin along x, y and z (a byte each) from the last binning of its node,
    /// which that node's partition reads instead of binning it again.
    uint32_t bins;

    int binAlong(int axis) const { return int(bins >> (8 * axis) & 0xffu); }
};
static_assert(sizeof(BuildRef) == 32);

/// The builders' reference arrays, sized without zeroing (they are filled in parallel).
using BuildRefs = UninitializedVector<BuildRef>;

/// A box in two SSE registers; the fourth lane is not part of it.
struct BuildBox {
    __m128 lower = _mm_set1_ps(std::numeric_limits<float>::infinity());
    __m128 upper = _mm_set1_ps(-std::numeric_limits<float>::infinity());

    BuildBox() = default;
    BuildBox(__m128 lo, __m128 hi) : lower(lo), upper(hi) {}
    /// The fourth lanes (the reference's prim and bins, denormal as floats) are zeroed: arithmetic on
    /// denormals is slow (2.5x the binning's time where FTZ and DAZ are off).
    explicit BuildBox(const BuildRef& r)
        : lower(_mm_blend_ps(_mm_load_ps(&r.lower.x), _mm_setzero_ps(), 8)),
          upper(_mm_blend_ps(_mm_load_ps(&r.upper.x), _mm_setzero_ps(), 8)) {}

    void grow(const BuildBox& b) { lower = _mm_min_ps(lower, b.lower); upper = _mm_max_ps(upper, b.upper); }
    void grow(__m128 p) { lower = _mm_min_ps(lower, p); upper = _mm_max_ps(upper, p); }
    void intersect(const BuildBox& b) { lower = _mm_max_ps(lower, b.lower); upper = _mm_min_ps(upper, b.upper); }

    /// Twice the center, the builders' centroid (no multiply needed to bin it).
    __m128 center2() const { return _mm_add_ps(lower, upper); }

    bool empty() const { return (_mm_movemask_ps(_mm_cmpgt_ps(lower, upper)) & 7) != 0; }

    /// Half the surface area, 0 when empty: the SAH's measure (only ratios of it matter).
    float halfArea() const {
        if (empty()) return 0.0f;
        const __m128 e = _mm_sub_ps(upper, lower);
        const __m128 rotated = _mm_shuffle_ps(e, e, _MM_SHUFFLE(3, 0, 2, 1));  // (y, z, x)
        const __m128 p = _mm_mul_ps(e, rotated);                               // (xy, yz, zx)
        alignas(16) float v[4];
        _mm_store_ps(v, p);
        return v[0] + v[1] + v[2];
    }

    float lowerAt(int axis) const { return lane(lower, axis); }
    float upperAt(int axis) const { return lane(upper, axis); }

    Bounds3f bounds() const {
        alignas(16) float lo[4], hi[4];
        _mm_store_ps(lo, lower);
        _mm_store_ps(hi, upper);
        return {{lo[0], lo[1], lo[2]}, {hi[0], hi[1], hi[2]}};
    }

    /// Writes the box into a reference, keeping its primitive.
    void storeInto(BuildRef& r) const {
        const uint32_t prim = r.prim;
        _mm_store_ps(&r.lower.x, lower);
        _mm_store_ps(&r.upper.x, upper);
        r.prim = prim;
        r.bins = 0;
    }

    /// All bits set in lane `axis` and none in the others: a blend mask for one axis's coordinate.
    static __m128 axisMask(int axis) {
        return _mm_castsi128_ps(_mm_cmpeq_epi32(_mm_setr_epi32(0, 1, 2, 3), _mm_set1_epi32(axis)));
    }

    static float lane(__m128 v, int i) {
        alignas(16) float f[4];
        _mm_store_ps(f, v);
        return f[i];
    }
};

/// One box per axis and bin, for the builders' bins. Raw registers rather than BuildBox, so that only
/// the bins in use are ever initialized (small nodes use few).
template <int MaxBins>
struct AxisBinBoxes {
    __m128 lower[3][MaxBins], upper[3][MaxBins];

    void clear(int bins) {
        for (int b = 0; b < bins; ++b)
            for (int a = 0; a < 3; ++a) {
                lower[a][b] = BuildBox().lower;
                upper[a][b] = BuildBox().upper;
            }
    }
    BuildBox box(int axis, int bin) const { return {lower[axis][bin], upper[axis][bin]}; }
    void grow(int axis, int bin, const BuildBox& box) {
        lower[axis][bin] = _mm_min_ps(lower[axis][bin], box.lower);
        upper[axis][bin] = _mm_max_ps(upper[axis][bin], box.upper);
    }
    void merge(const AxisBinBoxes& other, int bins) {
        for (int b = 0; b < bins; ++b)
            for (int a = 0; a < 3; ++a) grow(a, b, other.box(a, b));
    }
    /// The boxes of bins [0, bin] and (bin, bins) along `axis`.
    void sides(int axis, int bin, int bins, BuildBox& left, BuildBox& right) const {
        for (int b = 0; b < bins; ++b) (b <= bin ? left : right).grow(box(axis, b));
    }
};

inline BuildRef makeBuildRef(const Bounds3f& b, uint32_t prim) { return {b.lower, prim, b.upper, 0}; }

} // namespace wideray
