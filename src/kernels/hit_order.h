#pragma once
// The total order on hits that makes every kernel agree: nearer first, then smaller (geomId, primId).
#include <cstdint>

#include "core/ray.h"

#include "simd/isa_namespace.h"

namespace wideray {
inline namespace WIDERAY_ISA {

inline bool isCloser(float t, uint32_t geomId, uint32_t primId, const Hit& hit) {
    if (t != hit.t) return t < hit.t;
    return geomId != hit.geomId ? geomId < hit.geomId : primId < hit.primId;
}

/// A ray every kernel traces; anything else (NaN, infinities, zero direction, tnear > tfar) misses.
[[gnu::always_inline]] inline bool isValidRay(const Ray& r) {
    auto finite = [](float x) { return x - x == 0.0f; };
    return finite(r.ox) && finite(r.oy) && finite(r.oz) && finite(r.dx) && finite(r.dy) && finite(r.dz) &&
           (r.dx != 0.0f || r.dy != 0.0f || r.dz != 0.0f) && r.tnear == r.tnear && r.tfar == r.tfar &&
           r.tnear <= r.tfar && r.tnear < __builtin_huge_valf();
}

} // namespace WIDERAY_ISA
} // namespace wideray
