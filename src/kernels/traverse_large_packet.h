#pragma once
// Large packets (256 rays: a 16x16 pixel block) for coherent rays. Inner nodes are tested once for
// the whole packet with interval arithmetic over the packet's origins and reciprocal directions
// (Wald, Boulos, Shirley 2007, "Ray Tracing Deformable Scenes Using Dynamic Bounding Volume
// Hierarchies"; Boulos et al. 2007, "Packet-based Whitted and Distribution Ray Tracing"): one
// N-wide test replaces P per-packet tests. At a leaf, each K-wide sub-packet tests the leaf's box
// per ray and then its triangles, with the reference's arithmetic. Packets whose rays do not share
// a direction octant, or spread over more than a few degrees, are traced as ordinary K-wide packets.
#include "kernels/traverse_packet.h"

#include "simd/isa_namespace.h"

namespace wideray {
inline namespace WIDERAY_ISA {

/// The leaf's box as one child slot of its parent, tested per ray of a sub-packet.
struct LeafBox {
    float lower[3], upper[3];
};

/// Each sub-packet through tracePacket: rays that spread too far for interval culling.
template <int N, int K, bool AnyHit, class Leaves>
inline void traceSubPackets(const SceneView<N>& scene, const Ray* rays, int count, Hit* hitsOut, uint8_t* occludedOut,
                            TraversalCost* costsOut, IncoherentPackets* history, ShadowCache* cache) {
    for (int first = 0; first < count; first += K) {
        const int n = count - first < K ? count - first : K;
        tracePacket<N, K, AnyHit, Leaves>(scene, rays + first, n, AnyHit ? nullptr : hitsOut + first,
                                          AnyHit ? occludedOut + first : nullptr, costsOut ? costsOut + first : nullptr,
                                          history, cache);
    }
}

/// The P sub-packets of K rays of a large packet, with their hits so far.
template <int K, int P, bool Counting>
struct LargePacket {
    static_assert(P <= 64);
    PacketRay<K> packets[P];
    PacketHit<K> hits[P];
    PacketUserHits<K> users[P];
    PacketCost<K, Counting> costs[P];
    vbool<K> valid[P], done[P];
    int subCount = 0;
    uint64_t anyValid = 0;  ///< sub-packets with rays still to trace

    /// Loads up to K * P rays; returns whether all valid ones share one direction octant. The rays of
    /// the sub-packet kPrefetchAhead ahead are asked for meanwhile: a large packet reads its 9 KB of
    /// rays in one burst, which the hardware prefetcher does not see coming (`perf`: a fifth of the
    /// framed Sponza's camera-ray time went to loadPacket, most of it waiting on the rays; `packet256`
    /// 3-14% faster on the bunny and framed Sponza, ABBA on one CPU, 3-5 rounds).
    bool load(const Ray* rays, int count) {
        constexpr int kPrefetchAhead = 4;
        subCount = (count + K - 1) / K;
        bool oneOctant = true;
        for (int s = 0; s < subCount; ++s) {
            if ((s + kPrefetchAhead) * K < count) prefetchLines(rays + (s + kPrefetchAhead) * K, K * sizeof(Ray));
            valid[s] = loadPacket(rays + s * K, count - s * K < K ? count - s * K : K, packets[s], hits[s]);
            users[s] = PacketUserHits<K>(rays + s * K);
            done[s] = andNot(vbool<K>(true), valid[s]);
            if (none(valid[s])) continue;
            const PacketRay<K>& first = packets[__builtin_ctzll(anyValid | (uint64_t(1) << s))];
            oneOctant = oneOctant && packets[s].uniformOctant && packets[s].negXs == first.negXs &&
                        packets[s].negYs == first.negYs && packets[s].negZs == first.negZs;
            anyValid |= uint64_t(1) << s;
        }
        return oneOctant;
    }

    /// The bounds of the valid rays' origins and reciprocal directions (anyValid must not be 0).
    RayInterval interval() const {
        RayBounds<K> bounds;
        for (uint64_t bits = anyValid; bits; bits &= bits - 1) {
            const int s = __builtin_ctzll(bits);
            bounds.add(packets[s], valid[s]);
        }
        return bounds.interval(packets[__builtin_ctzll(anyValid)]);
    }

    /// The farthest culling distance among the unfinished rays.
    float tfarMax() const {
        using F = vfloat<K>;
        F m(-__builtin_huge_valf());
        for (uint64_t bits = anyValid; bits; bits &= bits - 1) {
            int s = __builtin_ctzll(bits);
            m = max(select(done[s], F(-__builtin_huge_valf()), hits[s].t), m);
        }
        return reduceMax(m);
    }

    /// The farthest culling distance among the unfinished rays of sub-packet s.
    float tfarMax(int s) const {
        using F = vfloat<K>;
        return reduceMax(select(done[s], F(-__builtin_huge_valf()), hits[s].t));
    }

    template <bool AnyHit>
    void write(int count, Hit* hitsOut, uint8_t* occludedOut, TraversalCost* costsOut) const {
        for (int s = 0; s < subCount; ++s) {
            const int n = count - s * K < K ? count - s * K : K;
            writePacketResults<K, AnyHit>(hits[s], users[s], movemask(valid[s]), movemask(done[s]), n,
                                          AnyHit ? nullptr : hitsOut + s * K, AnyHit ? occludedOut + s * K : nullptr);
            costs[s].write(n, costsOut ? costsOut + s * K : nullptr);
        }
    }
};

/// Leaves a large packet may enter before it gives up on interval culling. Where leaves are small
/// against the packet's beam (the country kitchen from its camera: 690 leaves entered per packet, 0.4%
/// of the sub-packets' leaf box tests hit), interval culling visits far more than the rays need; such
/// packets go on as K-wide packets from the root, culling by the hits found so far. Measured (camera /
/// shadow rays, 512x512): the kitchen interior 13.3 -> 27.1 / 3.5 -> 57.0 Mrays/s, the Sponza interior
/// 30.4 -> 25.5 / 26.0 -> 23.8 (it averages 53 leaves per packet), framed meshes unchanged; 128 and 256
/// kept less of the kitchen's gain and not more of Sponza's. Going on with the hits so far instead of
/// from scratch: leaves per camera ray 1.98 -> 1.87 (kitchen), 4.04 -> 3.90 (Sponza), per shadow ray
/// 2.16 -> 1.90 (Sponza).
constexpr int kLargePacketLeafBudget = 64;

/// Closest-hit large packets test a leaf's box against their sub-packets' intervals first, and only
/// the sub-packets that it enters test it ray by ray, while that pays: each window of this many
/// sub-packets at leaves decides for the next, by whether at least half of them missed (by interval
/// while on, by all their rays while off). Where leaves are small against the packet's beam (the
/// bunny, the dragon, Sponza from inside), most sub-packets miss most leaves; where they are large
/// (the Cornell box, Suzanne), the sub-packets' bounds (a tenth of a packet's time there) would not
/// pay. Not for any-hit: shadow rays' origins spread over the tile's surface, which doubles the cost
/// of the bounds, and their packets enter few leaves before they are occluded.
constexpr int kSubPacketWindow = 32;

/// Closest hits (or occlusion, through `cache` where given) of up to K * P rays, P sub-packets of K,
/// and their costs with `Counting` (an inner node tested for the packet counts for each of its
/// unfinished rays).
template <int N, int K, int P, bool AnyHit, bool Counting, class Leaves>
inline void traceLargePacketCounted(const SceneView<N>& scene, const Ray* rays, int count, Hit* hitsOut,
                                    uint8_t* occludedOut, TraversalCost* costsOut, IncoherentPackets* history,
                                    ShadowCache* cache) {
    using F = vfloat<K>;
    uint32_t* lastOccluder = cache ? &cache->found : nullptr;
    const Leaves leaves{scene.leaves, lastOccluder};
    LargePacket<K, P, Counting> lp;
    const bool oneOctant = lp.load(rays, count);
    if (!oneOctant || scene.root.isLeaf())
        return traceSubPackets<N, K, AnyHit, Leaves>(scene, rays, count, hitsOut, occludedOut, costsOut, history, cache);
    if (lp.anyValid) {
        const RayInterval iv = lp.interval();
        if (!narrowEnough(iv))
            return traceSubPackets<N, K, AnyHit, Leaves>(scene, rays, count, hitsOut, occludedOut, costsOut, history,
                                                         cache);
        if (AnyHit && cache)
            for (uint64_t bits = lp.anyValid; bits; bits &= bits - 1) {
                const int s = __builtin_ctzll(bits);
                occludeByCache(scene.leaves, *cache, lp.packets[s], lp.hits[s], lp.done[s]);
                if (all(lp.done[s])) lp.anyValid &= ~(uint64_t(1) << s);
            }
        struct Entry {
            NodeRef ref;
            float distance;  ///< where the packet's interval enters the subtree's box
            LeafBox box;
        };
        SubPacketIntervals<P> sub;
        bool bounded = false, bySubPacket = false;
        int subTested = 0, subSkipped = 0;  // since the last switch: sub-packets at leaves, and those that missed
        Entry stack[kStackSize<N>];
        int sp = 0;
        int leavesEntered = 0;
        if (lp.anyValid) stack[sp++] = {scene.root, iv.tnear, {}};
        float tfarMax = lp.tfarMax();
        while (sp > 0) {
            Entry e = stack[--sp];
            if (e.distance > tfarMax * kRobustFarScale) continue;
            if (!e.ref.isLeaf()) {
                const WideNode<N>& node = scene.nodes[e.ref.index()];
                if constexpr (Counting)
                    for (uint64_t bits = lp.anyValid; bits; bits &= bits - 1) {
                        const int s = __builtin_ctzll(bits);
                        lp.costs[s].visit(movemask(andNot(lp.valid[s], lp.done[s])));
                    }
                alignas(64) float tEntry[N];
                uint32_t mask = intersectChildrenInterval<N>(node, iv, tfarMax, tEntry);
                const int base = sp;
                for (; mask; mask &= mask - 1) {
                    int i = __builtin_ctz(mask);
                    if (node.child[i].bits == NodeRef::empty().bits) continue;
                    if (node.child[i].isLeaf()) leaves.prefetch(node.child[i]);
                    pushSorted(stack, base, sp,
                               Entry{node.child[i], tEntry[i],
                                     {{node.lowerX[i], node.lowerY[i], node.lowerZ[i]},
                                      {node.upperX[i], node.upperY[i], node.upperZ[i]}}});
                }
                continue;
            }
            if (++leavesEntered > kLargePacketLeafBudget) {
                // Each sub-packet goes on alone from the root, its hits so far culling its traversal.
                for (uint64_t bits = lp.anyValid; bits; bits &= bits - 1) {
                    const int s = __builtin_ctzll(bits);
                    traversePacket<N, K, AnyHit, Leaves>(scene, rays + s * K, lp.packets[s], lp.hits[s],
                                                         lp.users[s], lp.done[s], false, lp.costs[s], lastOccluder);
                }
                break;
            }
            const LeafBox& b = e.box;
            if (!AnyHit && subTested >= kSubPacketWindow && (subSkipped * 2 >= subTested) != bySubPacket) {
                bySubPacket = !bySubPacket;
                if (!bounded) sub.bound(lp.packets, lp.hits, lp.valid, lp.done, lp.anyValid, iv), bounded = true;
                subTested = subSkipped = 0;
            }
            uint64_t entered = lp.anyValid;
            if (bySubPacket) {
                entered &= sub.enter(b.lower, b.upper);
                subTested += __builtin_popcountll(lp.anyValid);
                subSkipped += __builtin_popcountll(lp.anyValid & ~entered);
            }
            for (uint64_t bits = entered; bits; bits &= bits - 1) {
                int s = __builtin_ctzll(bits);
                vbool<K> active = andNot(lp.valid[s], lp.done[s]);
                active &= packetBoxEntry(b.lower[0], b.lower[1], b.lower[2], b.upper[0], b.upper[1], b.upper[2],
                                         lp.packets[s], lp.hits[s].t, active) < F(__builtin_huge_valf());
                if (!AnyHit && !bySubPacket) ++subTested, subSkipped += none(active);
                if (none(active)) continue;
                const vbool<K> occluded =
                    leaves.template packet<K, AnyHit>(e.ref, lp.packets[s], active, lp.hits[s], lp.users[s], lp.costs[s]);
                if constexpr (AnyHit) {
                    lp.done[s] |= occluded;
                    if (all(lp.done[s])) lp.anyValid &= ~(uint64_t(1) << s);
                }
                if (bySubPacket) sub.narrow(s, lp.tfarMax(s));
            }
            if (AnyHit && !lp.anyValid) break;
            tfarMax = lp.tfarMax();
        }
    }
    if (cache) cache->remember();
    lp.template write<AnyHit>(count, hitsOut, occludedOut, costsOut);
}

/// Closest hits (or occlusion) of up to K * P rays, and their costs where `costsOut` is given;
/// `history` as tracePacket's, for the packets traced as K-wide ones; `cache`: any-hit's shadow cache,
/// where given.
template <int N, int K, int P, bool AnyHit, class Leaves = SceneLeafIntersector<N>>
inline void traceLargePacket(const SceneView<N>& scene, const Ray* rays, int count, Hit* hitsOut,
                             uint8_t* occludedOut, TraversalCost* costsOut = nullptr,
                             IncoherentPackets* history = nullptr, ShadowCache* cache = nullptr) {
    if (costsOut)
        return traceLargePacketCounted<N, K, P, AnyHit, true, Leaves>(scene, rays, count, hitsOut, occludedOut,
                                                                      costsOut, history, cache);
    traceLargePacketCounted<N, K, P, AnyHit, false, Leaves>(scene, rays, count, hitsOut, occludedOut, nullptr, history,
                                                            cache);
}

} // namespace WIDERAY_ISA
} // namespace wideray
