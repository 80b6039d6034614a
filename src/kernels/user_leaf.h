#pragma once
// The user-primitive leaves: each primitive asks its geometry (spheres, analytic primitives, CSG)
// to intersect the ray, or is a two-level instance, one ray at a time, for single rays and for the
// lanes of packets and streams alike.
#include "accel/bvh_view.h"
#include "core/geometry.h"
#include "kernels/hit_order.h"
#include "kernels/ray_state.h"

#include "simd/isa_namespace.h"

namespace wideray {
inline namespace WIDERAY_ISA {

/// One ray against the two-level instance `index`: closest-hit updates `hit` (and returns false),
/// any-hit returns whether it occludes the ray. Defined in kernels/instance_leaf.h.
template <int N, bool AnyHit>
bool intersectInstance(const InstanceTable& table, uint32_t index, const Ray& ray, Hit& hit, TraversalCost& cost);

/// One ray against the leaf's primitives; closest-hit updates `hit` (and returns false), any-hit
/// returns true at the first hit.
template <int N, bool AnyHit>
inline bool intersectUserLeaf(const SceneLeaves& leaves, NodeRef leaf, const Ray& ray, Hit& hit, TraversalCost& cost) {
    for (uint32_t i = leaf.first(); i < leaf.first() + leaf.count(); ++i) {
        ++cost.primitives;
        const PrimRef p = leaves.prims[i];
        if (leaves.instances && p.geomId == leaves.instances->geomId) {
            if (intersectInstance<N, AnyHit>(*leaves.instances, p.primId, ray, hit, cost)) return true;
            continue;
        }
        float t, u, v;
        if (!leaves.geometries[p.geomId]->intersect(ray, p.primId, hit.t, t, u, v)) continue;
        if constexpr (AnyHit) return true;
        if (isCloser(t, p.geomId, p.primId, hit)) hit = {t, u, v, p.primId, p.geomId};
    }
    return false;
}

/// The active lanes of a packet against the leaf's primitives, one lane at a time. Any-hit returns
/// the lanes found occluded (their t becomes -inf).
template <int N, int K, bool AnyHit, class UserHits, class Cost>
inline vbool<K> intersectUserLeafPacket(const SceneLeaves& leaves, NodeRef leaf, const vbool<K>& active,
                                        PacketHit<K>& h, UserHits& user, Cost& cost) {
    PacketLanes<K> lanes;
    lanes.store(h);
    for (uint32_t bits = movemask(active); bits; bits &= bits - 1) {
        const int lane = __builtin_ctz(bits);
        Hit hit = laneHit(lanes, user, lane);
        TraversalCost laneCost;
        if (intersectUserLeaf<N, AnyHit>(leaves, leaf, user.ray(lane), hit, laneCost)) lanes.t[lane] = -__builtin_huge_valf();
        else if constexpr (!AnyHit) setLaneHit(lanes, user, lane, hit);
        cost.add(lane, laneCost);
    }
    lanes.load(h);
    if constexpr (AnyHit) return active & (h.t == vfloat<K>(-__builtin_huge_valf()));
    return vbool<K>(false);
}

} // namespace WIDERAY_ISA
} // namespace wideray
