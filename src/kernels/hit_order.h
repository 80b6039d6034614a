#pragma once
// The total order on hits that makes every kernel agree: nearer first, then smaller (geomId, primId).
#include <cstddef>
#include <cstdint>

#include <immintrin.h>

#include "core/ray.h"

#include "simd/isa_namespace.h"

namespace wideray {
inline namespace WIDERAY_ISA {

inline bool isCloser(float t, uint32_t geomId, uint32_t primId, const Hit& hit) {
    if (t != hit.t) return t < hit.t;
    return geomId != hit.geomId ? geomId < hit.geomId : primId < hit.primId;
}

/// A ray every kernel traces; anything else (NaN, infinities, zero direction, tnear > tfar) misses.
/// Without a branch per field: a single ray that misses the scene costs little more than this test.
[[gnu::always_inline]] inline bool isValidRay(const Ray& r) {
    static_assert(offsetof(Ray, dx) == 3 * sizeof(float) && offsetof(Ray, tfar) == 7 * sizeof(float));
    const __m128 front = _mm_loadu_ps(&r.ox), back = _mm_loadu_ps(&r.dy);  // (ox, oy, oz, dx), (dy, dz, tnear, tfar)
    const __m128 zero = _mm_setzero_ps();
    // x - x is 0 for finite x, NaN for infinities and NaN.
    const int finite = _mm_movemask_ps(_mm_cmpeq_ps(_mm_sub_ps(front, front), zero)) |
                       (_mm_movemask_ps(_mm_cmpeq_ps(_mm_sub_ps(back, back), zero)) & 3) << 4;
    const int nonZeroDirection = (_mm_movemask_ps(_mm_cmpneq_ps(front, zero)) & 8) |
                                 (_mm_movemask_ps(_mm_cmpneq_ps(back, zero)) & 3);
    return (finite == 0x3f) & (nonZeroDirection != 0) & (r.tnear <= r.tfar) & (r.tnear < __builtin_huge_valf());
}

} // namespace WIDERAY_ISA
} // namespace wideray
