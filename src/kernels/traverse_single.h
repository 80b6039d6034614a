#pragma once
// Single-ray traversal of the wide BVH: children visited nearest first, subtrees beyond the closest
// hit culled, any-hit mode stopping at the first occluder. NodeW = 1 and TriW = 1 give the scalar
// reference; NodeW = N and TriW = kBlockSize give the same answers with SIMD box and triangle tests.
#include <cstdint>

#include "accel/bvh_view.h"
#include "kernels/box_test.h"
#include "kernels/child_order.h"
#include "kernels/hit_order.h"
#include "kernels/leaf_intersector.h"
#include "kernels/prefetch.h"

#include "simd/isa_namespace.h"

namespace wideray {
inline namespace WIDERAY_ISA {

template <int N>
constexpr int kStackSize = kMaxBvhDepth * (N - 1) + 1;

/// How many children of an N-wide node one SIMD box test covers in this ISA.
template <int N>
constexpr int kNodeSimdWidth = N < kMaxWidth ? N : kMaxWidth;

/// A subtree waiting on a single ray's traversal stack.
struct SingleRayEntry {
    NodeRef ref;
    float distance;  ///< where the ray enters the subtree's box
};

/// A single ray's step into the children `hits` (not none) of `node`: returns the child it goes on
/// to and pushes the others, nearest last with Ordered (entry distances in tEntry), in slot order
/// without. `pushed(ref)` is told each child pushed. The stack needs room for N entries beyond sp.
template <int N, bool Ordered, class PushedFn>
[[gnu::always_inline]] inline NodeRef descendIntoChildren(SingleRayEntry* stack, int& sp, const WideNode<N>& node,
                                                          uint32_t hits, const float* tEntry, const PushedFn& pushed) {
    const int first = __builtin_ctz(hits);
    uint32_t rest = hits & (hits - 1);
    if (rest == 0) return node.child[first];
    if constexpr (!Ordered) {
        for (; rest; rest &= rest - 1) {
            const NodeRef child = node.child[__builtin_ctz(rest)];
            stack[sp++] = {child, 0.0f};
            pushed(child);
        }
        return node.child[first];
    }
    if ((rest & (rest - 1)) == 0) {  // the most common case after one hit: no sort, one push
        const int second = __builtin_ctz(rest);
        const bool secondNearer = tEntry[second] < tEntry[first];
        const int nearer = secondNearer ? second : first, farther = secondNearer ? first : second;
        stack[sp++] = {node.child[farther], tEntry[farther]};
        pushed(node.child[farther]);
        return node.child[nearer];
    }
    const NodeRef next = pushNearestLast(stack, sp, node, hits, tEntry);  // three or more
    for (; hits; hits &= hits - 1) {
        const NodeRef child = node.child[__builtin_ctz(hits)];
        if (child.bits != next.bits) pushed(child);
    }
    return next;
}

/// Visits the leaves a ray reaches, nearest subtree first (with Ordered; otherwise in node order, which
/// any-hit traversal prefers: any occluder will do). `leaf(ref, cost)` returns true to stop (any-hit);
/// `tfar()` is the current culling distance, which without Ordered must not change but where `leaf`
/// stops: a pushed subtree is then never culled when popped, and entry distances are not computed.
/// Callers mark `leaf` always_inline: as a call it costs a vzeroupper and the node test's set-up again
/// after every leaf. Inner nodes are counted in `cost` with CountNodes only: the counter, kept across
/// the node loop, cost AVX2 single rays up to 13% where nobody reads it.
template <int N, int NodeW, bool Ordered, bool CountNodes, class LeafFn, class TfarFn>
inline void traverseWide(const WideNode<N>* nodes, NodeRef root, const BoxRay& box, float tnear, const TfarFn& tfar,
                         const LeafFn& leaf, TraversalCost& cost) {
    const ChildBoxTest<N, NodeW> intersectChildren(box);
    // Counted here and added to `cost` at the end: stores through `cost` could alias the ray's state
    // for all the compiler knows, which then reloads the leaf test's constants at every leaf.
    TraversalCost counted;
    SingleRayEntry stack[kStackSize<N> + N];  // room for the N entries pushNearestLast stores at once
    int sp = 0;
    stack[sp++] = {root, tnear};
    while (sp > 0) {
        SingleRayEntry e = stack[--sp];
        if (Ordered && e.distance > tfar() * kRobustFarScale) continue;
        NodeRef ref = e.ref;
        while (!ref.isLeaf()) {
            if constexpr (CountNodes) ++counted.nodes;
            const WideNode<N>& node = nodes[ref.index()];
            alignas(64) float tEntry[N];
            uint32_t hits;
            if constexpr (Ordered) hits = intersectChildren(node, tnear, tfar(), tEntry);
            else hits = intersectChildren.hits(node, tnear, tfar());
            if (hits == 0) goto pop;
            if constexpr (Ordered) prefetchFirstHits(nodes, node, hits);
            ref = descendIntoChildren<N, Ordered>(stack, sp, node, hits, tEntry, [](NodeRef) {});
        }
        if (leaf(ref, counted)) break;
    pop:;
    }
    cost += counted;
}

/// Closest hit (AnyHit = false) or occlusion (AnyHit = true, returns whether occluded) of one valid
/// ray in the subtree at `root`; `hit` holds the ray's closest hit so far (a miss at ray.tfar to begin).
/// `woop()` gives the ray's watertight constants (the SIMD kernels have them made already,
/// forEachRayState; traceSingle makes them). Closest-hit rays ask for them at the first leaf they
/// enter: most rays that miss enter none, and making them costs three divisions (the framed kitchen's
/// diffuse rays, nearly all misses, 1.4x faster with them made there). Any-hit rays start on surfaces
/// and nearly all enter a leaf, where waiting for the divisions cost the bunny's shadow rays 3-4%:
/// they make them before the traversal. Any-hit writes the block that occludes the ray to
/// `lastOccluder`, where given. Without CountNodes, `cost` gets no inner nodes (traverseWide).
template <int N, int NodeW, int TriW, bool AnyHit, class Leaves = SceneLeafIntersector<N>, bool CountNodes = true,
          class WoopFn>
inline bool traceSubtree(const SceneView<N>& scene, NodeRef root, const Ray& ray, const BoxRay& box, const WoopFn& woop,
                         Hit& hit, TraversalCost& cost, uint32_t* lastOccluder = nullptr) {
    const Leaves leaves{scene.leaves, lastOccluder};
    BlockRay<TriW> blockRay;
    bool blockRayMade = false, occluded = false;
    auto makeBlockRay = [&] {
        blockRay = BlockRay<TriW>(woop());
        blockRayMade = true;
    };
    if constexpr (AnyHit) makeBlockRay();
    traverseWide<N, NodeW, !AnyHit, CountNodes>(
        scene.nodes, root, box, ray.tnear, [&] { return hit.t; },
        [&](NodeRef leaf, TraversalCost& counted) __attribute__((always_inline)) {
            if (!AnyHit && !blockRayMade) makeBlockRay();
            return occluded = leaves.template single<TriW, AnyHit>(leaf, blockRay, ray, hit, counted);
        },
        cost);
    return occluded;
}

/// The same for the whole scene; invalid rays miss.
template <int N, int NodeW, int TriW, bool AnyHit, class Leaves = SceneLeafIntersector<N>, bool CountNodes = true>
inline bool traceSingle(const SceneView<N>& scene, const Ray& ray, Hit& hit, TraversalCost& cost) {
    if (!isValidRay(ray)) return false;
    return traceSubtree<N, NodeW, TriW, AnyHit, Leaves, CountNodes>(scene, scene.root, ray, makeBoxRay(ray),
                                                        [&] { return makeWatertightRay(ray); }, hit, cost);
}

} // namespace WIDERAY_ISA
} // namespace wideray

#include "kernels/instance_leaf.h"  // intersectInstance, which the leaf intersector calls
