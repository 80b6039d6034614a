#pragma once
// The leaf intersector of a scene's BVH: what every traversal kind (single rays, packets, large
// packets, streams) calls at a leaf, by the leaf's type: triangle blocks or user primitives (two-level
// instances among them). A new leaf type (another triangle layout) is a new branch here; the
// traversals stay as they are.
#include "kernels/prefetch.h"
#include "kernels/triangle_leaf.h"
#include "kernels/user_leaf.h"

#include "simd/isa_namespace.h"

namespace wideray {
inline namespace WIDERAY_ISA {

template <int N>
struct SceneLeafIntersector {
    SceneLeaves leaves;
    /// Where given, any-hit tests write the triangle block that last occluded a ray (the shadow cache's
    /// block; never one of an instance's mesh, whose traversal has its own intersector).
    uint32_t* lastOccluder = nullptr;

    /// One ray; closest-hit updates `hit`, any-hit returns true when the leaf occludes the ray.
    /// TriW = 1 tests a block's triangles one by one (the reference), kBlockSize all at once.
    template <int TriW, bool AnyHit>
    [[gnu::always_inline]] bool single(NodeRef leaf, const BlockRay<TriW>& r, const Ray& ray, Hit& hit,
                                       TraversalCost& cost) const {
        ++cost.leaves;
        if (leaf.isUserLeaf()) return intersectUserLeaf<N, AnyHit>(leaves, leaf, ray, hit, cost);
        for (uint32_t b = leaf.first(); b < leaf.first() + leaf.count(); ++b) {
            cost.primitives += kBlockSize;
            if (intersectBlock<TriW, AnyHit>(leaves.blocks[b], r, ray, hit)) {
                if (lastOccluder) *lastOccluder = b;
                return true;
            }
        }
        return false;
    }

    /// Asks for a triangle leaf's blocks ahead of their test.
    [[gnu::always_inline]] void prefetch(NodeRef leaf) const {
        if (!leaf.isUserLeaf()) prefetchLines(leaves.blocks + leaf.first(), leaf.count() * sizeof(TriangleBlock<kBlockSize>));
    }

    /// The active lanes of a packet; any-hit returns the lanes the leaf occludes (their t becomes
    /// -inf). Packets whose triangles are tested need the watertight fields of `p`. `cost` counts
    /// per lane (PacketCost or the stream's).
    template <int K, bool AnyHit, class UserHits, class Cost>
    [[gnu::always_inline]] vbool<K> packet(NodeRef leaf, const PacketRay<K>& p, vbool<K> active, PacketHit<K>& h,
                                           UserHits& user, Cost& cost) const {
        cost.enter(movemask(active));
        if (leaf.isUserLeaf()) return intersectUserLeafPacket<N, K, AnyHit>(leaves, leaf, active, h, user, cost);
        vbool<K> occluded(false);
        for (uint32_t b = leaf.first(); b < leaf.first() + leaf.count(); ++b) {
            cost.test(movemask(active), kBlockSize);
            if constexpr (AnyHit) {
                const vbool<K> hit = occludeByBlock(leaves.blocks[b], p, active, h);
                if (lastOccluder && any(hit)) *lastOccluder = b;
                occluded |= hit;
                active = andNot(active, hit);
                if (none(active)) break;
            } else {
                intersectBlockPacket<K, false>(leaves.blocks[b], p, active, h);
            }
        }
        return occluded;
    }
};

/// Asks for what a traversal reads first at `child`: its node, or its leaf's triangle blocks.
template <int N>
[[gnu::always_inline]] inline void prefetchChild(const SceneView<N>& scene, NodeRef child) {
    if (child.isLeaf()) SceneLeafIntersector<N>{scene.leaves}.prefetch(child);
    else prefetchNode(scene.nodes, child);
}

} // namespace WIDERAY_ISA
} // namespace wideray
