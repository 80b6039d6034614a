#pragma once
// A few single rays through the same subtree at once, taking turns: each ray tests one node or leaf
// per turn and asks for what it reads next before the next ray takes its turn, so that the cache
// misses of rays that go on to different parts of the subtree overlap instead of coming one ray after
// another (the software pipelining of independent pointer chases). Each ray visits what
// `traverseWide` visits, in its order, with the same box and triangle tests: the hits are the same.
// The stream's short lists take this way (their rays are deep in the tree, where no other ray of the
// stream has been, and their reads mostly miss): `stream` 7% and 11% faster on Sponza's diffuse and
// bounce rays from inside (high build; 3% and 10% on the fast build) and 13% and 10% on the kitchen's,
// the same on framed meshes whose trees stay in cache (ABBA, 4-5 rounds, `single` as the control).
// Packets' lanes finishing alone do not: 11-23% slower on incoherent rays from inside Sponza (a
// packet's rays go on to neighbouring nodes, which are in cache, and a turn reloads the ray's state
// that a whole traversal keeps in registers).
#include <cstdint>

#include "kernels/traverse_single.h"

#include "simd/isa_namespace.h"

namespace wideray {
inline namespace WIDERAY_ISA {

/// One ray's traversal, kept between its turns. The caller sets `ray`, `state`, `hit` (its closest
/// hit so far), `next` (the root of its subtree) and zeroes `cost`; `occluded` and `hit` are the answers.
template <int N>
struct InterleavedRay {
    const Ray* ray;
    SingleRayState state;
    Hit hit;
    TraversalCost cost;
    bool occluded;
    NodeRef next;  ///< what its next turn reads
    int sp;
    SingleRayEntry stack[kStackSize<N> + N];  // left uninitialized: room for pushNearestLast's N stores
};

/// One turn of ray `r`: a node's children tested (the next child chosen, the others pushed) or a leaf
/// intersected; then the next node or leaf it reads is asked for. Returns false when the ray is done.
/// The children it pushes are asked for too (before taking turns, when the stream's rays finished one
/// by one, that alone made `stream` 3-5% faster on Sponza's diffuse and bounce rays from inside and
/// 6-12% on the kitchen's; `single` asks only for the first two inner nodes it hits, prefetchFirstHits:
/// asking for all it pushes made its camera rays 2-4% slower).
template <int N, bool AnyHit, class Leaves>
[[gnu::always_inline]] inline bool interleavedTurn(const SceneView<N>& scene, const Leaves& leaves,
                                                   InterleavedRay<N>& r) {
    constexpr bool Ordered = !AnyHit;
    constexpr int NodeW = kNodeSimdWidth<N>;
    if (!r.next.isLeaf()) {
        ++r.cost.nodes;
        const WideNode<N>& node = scene.nodes[r.next.index()];
        const ChildBoxTest<N, NodeW> test(r.state.box);
        alignas(64) float tEntry[N];
        uint32_t hits;
        if constexpr (Ordered) hits = test(node, r.ray->tnear, r.hit.t, tEntry);
        else hits = test.hits(node, r.ray->tnear, r.hit.t);
        if (hits != 0) {
            auto prefetch = [&](NodeRef child) __attribute__((always_inline)) { prefetchChild(scene, child); };
            r.next = descendIntoChildren<N, Ordered>(r.stack, r.sp, node, hits, tEntry, prefetch);
            prefetchChild(scene, r.next);
            return true;
        }
    } else if (leaves.template single<kBlockSize, AnyHit>(r.next, BlockRay<kBlockSize>(r.state.woop), *r.ray, r.hit,
                                                          r.cost)) {
        r.occluded = true;
        return false;
    }
    while (r.sp > 0) {
        const SingleRayEntry e = r.stack[--r.sp];
        if (Ordered && e.distance > r.hit.t * kRobustFarScale) continue;
        r.next = e.ref;  // asked for when it was pushed
        return true;
    }
    return false;
}

/// Closest hits (AnyHit = false) or occlusion of the first `count` rays, each in its subtree, taking
/// turns.
template <int N, bool AnyHit, int MaxRays, class Leaves>
inline void traceInterleaved(const SceneView<N>& scene, const Leaves& leaves, InterleavedRay<N> (&rays)[MaxRays],
                             int count) {
    int live[MaxRays];
    for (int i = 0; i < count; ++i) {
        rays[i].occluded = false;
        rays[i].sp = 0;
        live[i] = i;
    }
    while (count > 0) {
        for (int k = 0; k < count;) {
            if (interleavedTurn<N, AnyHit>(scene, leaves, rays[live[k]])) ++k;
            else live[k] = live[--count];
        }
    }
}

} // namespace WIDERAY_ISA
} // namespace wideray
