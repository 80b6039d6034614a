#pragma once
// The binary BVH two ways: with a stack, nearest child first (bvh2), and without one along the miss
// links of its depth-first layout (skip), which fixes the order children are visited in.
#include "kernels/box_test.h"
#include "kernels/primitive_leaf.h"

#include "simd/isa_namespace.h"

namespace wideray {
inline namespace WIDERAY_ISA {

/// The ray's entry and exit distances through a box, with the slab test every kernel runs.
[[gnu::always_inline]] inline bool intersectBox(const BoxPlanes& box, const BoxRay& r, float tnear, float tfar,
                                                float& tEntry, float& tExit) {
    slabInterval(box.plane[r.nearPlane[0]], box.plane[r.farPlane[0]], box.plane[r.nearPlane[1]],
                 box.plane[r.farPlane[1]], box.plane[r.nearPlane[2]], box.plane[r.farPlane[2]], r.slab, tnear, tfar,
                 tEntry, tExit);
    return tEntry <= tExit;
}

/// Closest-hit updates `hit`; any-hit returns true at the first occluder.
template <bool AnyHit>
inline bool traceBvh2(const Bvh2View& bvh, const Ray& ray, Hit& hit, TraversalCost& cost) {
    if (!bvh.nodes || !isValidRay(ray)) return false;
    const SingleRayState s = makeSingleRayState(ray);
    float tEntry, tExit;
    if (!intersectBox(bvh.nodes[0].box, s.box, ray.tnear, hit.t, tEntry, tExit)) return false;
    struct Entry {
        uint32_t node;
        float distance;
    };
    Entry stack[kMaxBvhDepth + 1];
    int sp = 0;
    uint32_t node = 0;
    for (;;) {
        const Bvh2Node& n = bvh.nodes[node];
        if (n.count == 0) {
            ++cost.nodes;
            float entry[2], exit;
            const bool hit0 = intersectBox(bvh.nodes[n.first].box, s.box, ray.tnear, hit.t, entry[0], exit);
            const bool hit1 = intersectBox(bvh.nodes[n.first + 1].box, s.box, ray.tnear, hit.t, entry[1], exit);
            if (hit0 && hit1) {
                const int nearer = entry[1] < entry[0] ? 1 : 0;
                stack[sp++] = {n.first + 1 - nearer, entry[1 - nearer]};
                node = n.first + nearer;
                continue;
            }
            if (hit0 || hit1) {
                node = n.first + (hit0 ? 0 : 1);
                continue;
            }
        } else if (intersectItems<AnyHit>(bvh.prims, bvh.items + n.first, n.count, s, ray, hit, nullptr, cost)) {
            return true;
        }
        // Next: the nearest pushed subtree the ray may still reach.
        for (;;) {
            if (sp == 0) return false;
            const Entry& e = stack[--sp];
            if (AnyHit || e.distance <= hit.t) {
                node = e.node;
                break;
            }
        }
    }
}

template <bool AnyHit>
inline bool traceSkip(const SkipView& tree, const Ray& ray, Hit& hit, TraversalCost& cost) {
    if (!isValidRay(ray)) return false;
    const SingleRayState s = makeSingleRayState(ray);
    for (uint32_t i = 0; i < tree.nodeCount;) {
        const SkipNode& n = tree.nodes[i];
        float tEntry, tExit;
        if (!intersectBox(n.box, s.box, ray.tnear, hit.t, tEntry, tExit)) {
            i = n.skip;
            continue;
        }
        if (n.count == 0) {
            ++cost.nodes;
            ++i;
            continue;
        }
        if (intersectItems<AnyHit>(tree.prims, tree.items + n.first, n.count, s, ray, hit, nullptr, cost)) return true;
        i = n.skip;
    }
    return false;
}

} // namespace WIDERAY_ISA
} // namespace wideray
