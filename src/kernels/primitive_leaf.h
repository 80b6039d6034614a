#pragma once
// One ray against single primitives by item index (accel/course_views.h): what the leaves and cells of
// the course's structures call. Triangles take the reference's watertight test with the same operands,
// so every structure returns the reference's hits bit for bit. The mailbox remembers the items a ray
// has tested, for the structures that list a primitive in several leaves or cells.
#include <cstdint>

#include "accel/course_views.h"
#include "core/geometry.h"
#include "kernels/hit_order.h"
#include "kernels/ray_state.h"

#include "simd/isa_namespace.h"

namespace wideray {
inline namespace WIDERAY_ISA {

/// Closest-hit updates `hit` (and returns false); any-hit returns true when the item occludes.
template <bool AnyHit>
[[gnu::always_inline]] inline bool intersectItem(const PrimitiveView& prims, uint32_t item, const SingleRayState& s,
                                                 const Ray& ray, Hit& hit, TraversalCost& cost) {
    ++cost.primitives;
    float t = 0, u = 0, v = 0;
    if (item < prims.triangleCount) {
        const TriangleVertices& tri = prims.triangles[item];
        if (!intersectWatertight(s.woop, true, tri.v0x, tri.v0y, tri.v0z, tri.v1x, tri.v1y, tri.v1z, tri.v2x, tri.v2y,
                                 tri.v2z, ray.tnear, hit.t, t, u, v))
            return false;
        if constexpr (AnyHit) return true;
        if (isCloser(t, 0, item, hit)) hit = {t, u, v, item, 0};
        return false;
    }
    const PrimRef p = prims.users[item - prims.triangleCount];
    if (!prims.geometries[p.geomId]->intersect(ray, p.primId, hit.t, t, u, v)) return false;
    if constexpr (AnyHit) return true;
    if (isCloser(t, p.geomId, p.primId, hit)) hit = {t, u, v, p.primId, p.geomId};
    return false;
}

/// A ray's mailbox (Amanatides and Woo 1987; Kirk and Arvo 1991): the last items it tested, in a small
/// direct-mapped table of its own, so that threads share no state. Testing an item twice gives the
/// same answer as the first time (hit.t only shrinks), so a forgotten item costs a test, never a hit.
class Mailbox {
public:
    static constexpr uint32_t kSize = 32;  // a power of two

    /// True if `item` was tested already; otherwise remembers it.
    bool seen(uint32_t item) {
        uint32_t& slot = slots_[item & (kSize - 1)];
        if (slot == item) return true;
        slot = item;
        return false;
    }

private:
    uint32_t slots_[kSize] = {UINT32_MAX, UINT32_MAX, UINT32_MAX, UINT32_MAX, UINT32_MAX, UINT32_MAX, UINT32_MAX,
                              UINT32_MAX, UINT32_MAX, UINT32_MAX, UINT32_MAX, UINT32_MAX, UINT32_MAX, UINT32_MAX,
                              UINT32_MAX, UINT32_MAX, UINT32_MAX, UINT32_MAX, UINT32_MAX, UINT32_MAX, UINT32_MAX,
                              UINT32_MAX, UINT32_MAX, UINT32_MAX, UINT32_MAX, UINT32_MAX, UINT32_MAX, UINT32_MAX,
                              UINT32_MAX, UINT32_MAX, UINT32_MAX, UINT32_MAX};
};

/// A leaf's or cell's items; with a mailbox (structures that list a primitive in several leaves or
/// cells), each tested once per ray.
template <bool AnyHit>
[[gnu::always_inline]] inline bool intersectItems(const PrimitiveView& prims, const uint32_t* items, uint32_t count,
                                                  const SingleRayState& s, const Ray& ray, Hit& hit, Mailbox* mailbox,
                                                  TraversalCost& cost) {
    ++cost.leaves;
    for (uint32_t i = 0; i < count; ++i) {
        if (mailbox && mailbox->seen(items[i])) {
            ++cost.mailboxHits;
            continue;
        }
        if (intersectItem<AnyHit>(prims, items[i], s, ray, hit, cost)) return true;
    }
    return false;
}

} // namespace WIDERAY_ISA
} // namespace wideray
