#pragma once
// The kd-tree's front-to-back traversal (the recursive near/far walk of Sung and Shirley, Graphics
// Gems III, with its recursion as an explicit stack): each node's interval of the ray is split at the
// plane; the child the ray meets first is walked first, the other pushed with its part.
#include <cmath>

#include "kernels/traverse_bvh2.h"

#include "simd/isa_namespace.h"

namespace wideray {
inline namespace WIDERAY_ISA {

/// The plane's distance is widened by this much (relative) on both sides, so that a ray crossing the
/// plane near a node's corner walks both children rather than skipping one to rounding.
constexpr float kKdPlaneSlack = 0x1p-16f;

template <bool AnyHit>
inline bool traceKdTree(const KdTreeView& tree, const Ray& ray, Hit& hit, TraversalCost& cost) {
    if (!tree.nodes || !isValidRay(ray)) return false;
    const SingleRayState s = makeSingleRayState(ray);
    float tmin, tmax;
    if (!intersectBox(tree.bounds, s.box, ray.tnear, ray.tfar, tmin, tmax)) return false;
    const float origin[3] = {ray.ox, ray.oy, ray.oz};
    const float rdir[3] = {s.box.slab.rdx, s.box.slab.rdy, s.box.slab.rdz};
    struct Entry {
        uint32_t node;
        float tmin, tmax;
    };
    Entry stack[kMaxKdTreeDepth + 1];
    int sp = 0;
    uint32_t node = 0;
    Mailbox mailbox;
    // The next pushed node the ray may still need. Pushed intervals are not ordered where a ray
    // lying in a plane walked both children over the same interval, so a far one is skipped, not
    // taken for the end of the walk.
    auto pop = [&] {
        while (sp > 0) {
            const Entry& e = stack[--sp];
            if (!AnyHit && hit.t < e.tmin) continue;
            node = e.node;
            tmin = e.tmin;
            tmax = e.tmax;
            return true;
        }
        return false;
    };
    for (;;) {
        const KdNode& n = tree.nodes[node];
        if (!n.isLeaf()) {
            ++cost.nodes;
            const uint32_t a = n.axis();
            const float tPlane = (n.split - origin[a]) * rdir[a];
            // Before the plane the ray is on the side its direction leaves (for a zero component,
            // the side of its origin: the plane's distance is then +-inf, or NaN in the plane).
            const bool upperFirst = std::signbit(rdir[a]);
            const uint32_t first = upperFirst ? n.upperChild() : node + 1;
            const uint32_t second = upperFirst ? node + 1 : n.upperChild();
            if (tPlane != tPlane) {  // the ray lies in the plane: both sides, over the whole interval
                stack[sp++] = {second, tmin, tmax};
                node = first;
                continue;
            }
            const float slack = std::fabs(tPlane) < __builtin_huge_valf() ? std::fabs(tPlane) * kKdPlaneSlack : 0.0f;
            const float lo = tPlane - slack, hi = tPlane + slack;
            if (lo > tmax) {
                node = first;
            } else if (hi < tmin) {
                node = second;
            } else {
                stack[sp++] = {second, lo > tmin ? lo : tmin, tmax};
                node = first;
                tmax = hi < tmax ? hi : tmax;
            }
            continue;
        }
        if (intersectItems<AnyHit>(tree.prims, tree.items + n.firstItem(), n.count(), s, ray, hit, &mailbox, cost))
            return true;
        // A closer hit than where a node starts skips it: everything in it lies beyond.
        if (!pop()) return false;
    }
}

} // namespace WIDERAY_ISA
} // namespace wideray
