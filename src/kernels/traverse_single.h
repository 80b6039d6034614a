#pragma once
// Single-ray traversal of the wide BVH: children visited nearest first, subtrees beyond the closest
// hit culled, any-hit mode stopping at the first occluder. NodeW = 1 and TriW = 1 give the scalar
// reference; NodeW = N and TriW = kBlockSize give the same answers with SIMD box and triangle tests.
#include <cstdint>

#include "accel/bvh_view.h"
#include "core/geometry.h"
#include "kernels/box_test.h"
#include "kernels/hit_order.h"
#include "kernels/watertight.h"

#include "simd/isa_namespace.h"

namespace wideray {
inline namespace WIDERAY_ISA {

template <int N>
constexpr int kStackSize = kMaxBvhDepth * (N - 1) + 1;

/// How many children of an N-wide node one SIMD box test covers in this ISA.
template <int N>
constexpr int kNodeSimdWidth = N < kMaxWidth ? N : kMaxWidth;

struct SingleRayState {
    BoxRay box;
    WatertightRay<float, int32_t> woop;
};

inline SingleRayState makeSingleRayState(const Ray& ray) {
    return {makeBoxRay(ray.ox, ray.oy, ray.oz, ray.dx, ray.dy, ray.dz),
            makeWatertightRay<float, int32_t>(ray.ox, ray.oy, ray.oz, ray.dx, ray.dy, ray.dz)};
}

/// Tests one triangle block; closest-hit updates `hit` (and returns false), any-hit returns true
/// at the first hit.
template <int TriW, bool AnyHit>
inline bool intersectBlock(const TriangleBlock<kBlockSize>& block, const SingleRayState& s, const Ray& ray,
                           Hit& hit) {
    if constexpr (TriW == 1) {
        for (int i = 0; i < kBlockSize && block.primId[i] != kInvalidId; ++i) {
            float t = 0, u = 0, v = 0;
            bool h = intersectWatertight(s.woop, true, block.v0x[i], block.v0y[i], block.v0z[i], block.v1x[i],
                                         block.v1y[i], block.v1z[i], block.v2x[i], block.v2y[i], block.v2z[i],
                                         ray.tnear, hit.t, t, u, v);
            if (!h) continue;
            if constexpr (AnyHit) return true;
            if (isCloser(t, 0, block.primId[i], hit)) hit = {t, u, v, block.primId[i], 0};
        }
        return false;
    } else {
        static_assert(TriW == kBlockSize);
        // One ray: its axes are scalars, so the block's coordinate arrays are picked by pointer.
        using F = vfloat<TriW>;
        using I = vint<TriW>;
        const WatertightRay<float, int32_t>& w = s.woop;
        const float* v0[3] = {block.v0x, block.v0y, block.v0z};
        const float* v1[3] = {block.v1x, block.v1y, block.v1z};
        const float* v2[3] = {block.v2x, block.v2y, block.v2z};
        const float o[3] = {w.ox, w.oy, w.oz};
        const F ox(o[w.kx]), oy(o[w.ky]), oz(o[w.kz]);
        auto valid = I::loadu(block.primId) != I(int32_t(kInvalidId));
        F t(0.0f), u(0.0f), v(0.0f);
        auto h = intersectWatertightPermuted(
            F(w.sx), F(w.sy), F(w.sz), valid, F::load(v0[w.kx]) - ox, F::load(v0[w.ky]) - oy, F::load(v0[w.kz]) - oz,
            F::load(v1[w.kx]) - ox, F::load(v1[w.ky]) - oy, F::load(v1[w.kz]) - oz, F::load(v2[w.kx]) - ox,
            F::load(v2[w.ky]) - oy, F::load(v2[w.kz]) - oz, F(ray.tnear), F(hit.t), t, u, v);
        uint32_t lanes = movemask(h);
        if (!lanes) return false;
        if constexpr (AnyHit) return true;
        alignas(64) float ts[TriW], us[TriW], vs[TriW];
        t.store(ts); u.store(us); v.store(vs);
        for (; lanes; lanes &= lanes - 1) {
            int i = __builtin_ctz(lanes);
            if (isCloser(ts[i], 0, block.primId[i], hit)) hit = {ts[i], us[i], vs[i], block.primId[i], 0};
        }
        return false;
    }
}

/// Visits the leaves a ray reaches, nearest subtree first. `leaf(first, count)` returns true to stop
/// (any-hit); `tfar()` is the current culling distance.
template <int N, int NodeW, class LeafFn, class TfarFn>
inline void traverseWide(const WideNode<N>* nodes, NodeRef root, const BoxRay& box, float tnear, TfarFn tfar,
                         LeafFn leaf, TraversalCost& cost) {
    struct Entry {
        NodeRef ref;
        float tEntry;
    };
    Entry stack[kStackSize<N>];
    int sp = 0;
    stack[sp++] = {root, tnear};
    while (sp > 0) {
        Entry e = stack[--sp];
        if (e.tEntry > tfar() * kRobustFarScale) continue;
        NodeRef ref = e.ref;
        while (!ref.isLeaf()) {
            ++cost.nodes;
            const WideNode<N>& node = nodes[ref.index()];
            alignas(64) float tEntry[N];
            uint32_t mask = intersectChildren<N, NodeW>(node, box, tnear, tfar(), tEntry);
            if (mask == 0) goto pop;
            if ((mask & (mask - 1)) == 0) {
                ref = node.child[__builtin_ctz(mask)];
                continue;
            }
            // Insert the hit children into the stack sorted farthest first, then take the nearest.
            const int base = sp;
            for (; mask; mask &= mask - 1) {
                int i = __builtin_ctz(mask);
                Entry c{node.child[i], tEntry[i]};
                int j = sp++;
                for (; j > base && stack[j - 1].tEntry < c.tEntry; --j) stack[j] = stack[j - 1];
                stack[j] = c;
            }
            ref = stack[--sp].ref;
        }
        if (leaf(ref.first(), ref.count())) return;
    pop:;
    }
}

/// The user geometry (spheres) part of a single-ray trace; returns true when occluded (any-hit).
template <int N, int NodeW, bool AnyHit>
inline bool traceUser(const UserBvhView<N>& user, const Ray& ray, const SingleRayState& s, Hit& hit,
                      TraversalCost& cost) {
    bool occluded = false;
    traverseWide<N, NodeW>(
        user.nodes, user.root, s.box, ray.tnear, [&] { return hit.t; },
        [&](uint32_t first, uint32_t count) {
            for (uint32_t i = first; i < first + count; ++i) {
                ++cost.primitives;
                PrimRef p = user.prims[i];
                float t, u, v;
                if (!user.geometries[p.geomId]->intersect(ray, p.primId, hit.t, t, u, v)) continue;
                if (AnyHit) return occluded = true;
                if (isCloser(t, p.geomId, p.primId, hit)) hit = {t, u, v, p.primId, p.geomId};
            }
            return false;
        },
        cost);
    return occluded;
}

/// Closest hit (AnyHit = false) or occlusion (AnyHit = true, returns whether occluded) of one ray
/// against the scene's triangles and user geometry. `hit` must start as a miss at ray.tfar.
template <int N, int NodeW, int TriW, bool AnyHit>
inline bool traceSingle(const SceneView<N>& scene, const Ray& ray, Hit& hit, TraversalCost& cost) {
    if (!isValidRay(ray)) return false;
    const SingleRayState s = makeSingleRayState(ray);
    const TriangleBvhView<N>& tri = scene.triangles;
    if (tri.blocks) {
        bool occluded = false;
        traverseWide<N, NodeW>(
            tri.nodes, tri.root, s.box, ray.tnear, [&] { return hit.t; },
            [&](uint32_t first, uint32_t count) {
                for (uint32_t b = first; b < first + count; ++b) {
                    cost.primitives += kBlockSize;
                    if (intersectBlock<TriW, AnyHit>(tri.blocks[b], s, ray, hit)) return occluded = true;
                }
                return false;
            },
            cost);
        if (occluded) return true;
    }
    return scene.user.prims && traceUser<N, NodeW, AnyHit>(scene.user, ray, s, hit, cost);
}

} // namespace WIDERAY_ISA
} // namespace wideray
