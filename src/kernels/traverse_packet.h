#pragma once
// Packet traversal: K rays (a 2x2, 4x2 or 4x4 pixel block for K = 4, 8, 16) walk the wide BVH
// together. Each child box is tested against all active rays in one K-wide operation; a subtree is
// entered with the rays that hit its box, less those whose closest hit lies before the subtree's
// nearest entry, and left to single-ray traversal once few rays remain active (Wald et al. 2001,
// "Interactive Rendering with Coherent Ray Tracing"; Embree's hybrid packet/single-ray scheme,
// Benthin et al. 2012).
// Incoherent packets whose rays mostly hit, or start far apart, go on one ray at a time from the
// first node where they part (IncoherentPackets). Leaves run the reference's arithmetic per lane, so
// results are bit-identical.
#include <cstdint>

#include "kernels/incoherent_packets.h"
#include "kernels/ray_interval.h"
#include "kernels/shadow_cache.h"
#include "kernels/traverse_single.h"

#include "simd/isa_namespace.h"

namespace wideray {
inline namespace WIDERAY_ISA {

/// Entry distances of the packet into a box; +inf for rays that miss it or are inactive.
template <int K>
[[gnu::always_inline]] inline vfloat<K> packetBoxEntry(float lowerX, float lowerY, float lowerZ, float upperX,
                                                       float upperY, float upperZ, const PacketRay<K>& p,
                                                       const vfloat<K>& tfar, const vbool<K>& active) {
    using F = vfloat<K>;
    F nearX, farX, nearY, farY, nearZ, farZ;
    if (p.uniformOctant) {
        nearX = F(p.negXs ? upperX : lowerX); farX = F(p.negXs ? lowerX : upperX);
        nearY = F(p.negYs ? upperY : lowerY); farY = F(p.negYs ? lowerY : upperY);
        nearZ = F(p.negZs ? upperZ : lowerZ); farZ = F(p.negZs ? lowerZ : upperZ);
    } else {
        F lx(lowerX), ux(upperX), ly(lowerY), uy(upperY), lz(lowerZ), uz(upperZ);
        nearX = select(p.negX, ux, lx); farX = select(p.negX, lx, ux);
        nearY = select(p.negY, uy, ly); farY = select(p.negY, ly, uy);
        nearZ = select(p.negZ, uz, lz); farZ = select(p.negZ, lz, uz);
    }
    F tEntry, tExit;
    slabInterval(nearX, farX, nearY, farY, nearZ, farZ, p.slab, p.tnear, tfar, tEntry, tExit);
    return select(active & (tEntry <= tExit), tEntry, F(__builtin_huge_valf()));
}

/// Entry distances of the packet into child i of a node.
template <int N, int K>
[[gnu::always_inline]] inline vfloat<K> packetChildEntry(const WideNode<N>& node, int i, const PacketRay<K>& p,
                                                         const vfloat<K>& tfar, const vbool<K>& active) {
    return packetBoxEntry(node.lowerX[i], node.lowerY[i], node.lowerZ[i], node.upperX[i], node.upperY[i],
                          node.upperZ[i], p, tfar, active);
}

#if defined(__AVX512F__)
/// Writes the first `count` of 16 hits, given field by field (t, u, v, primId, geomId: Hit's layout),
/// as five 64-byte stores: Hit array dword k is field k % 5 of lane k / 5, so each store gathers its
/// dwords from the five fields by masked permutes.
inline void storeHits16(const vfloat16& t, const vfloat16& u, const vfloat16& v, const vint16& primId,
                        const vint16& geomId, int count, Hit* out) {
    static_assert(sizeof(Hit) == 20 && offsetof(Hit, primId) == 12 && offsetof(Hit, geomId) == 16);
    struct Tables {
        int32_t lane[5][16];      ///< [store][dword]: the lane it comes from
        uint16_t fieldMask[5][5];  ///< [store][field]: the dwords that field fills
    };
    static constexpr Tables kTables = [] {
        Tables tables{};
        for (int k = 0; k < 80; ++k) {
            tables.lane[k / 16][k % 16] = k / 5;
            tables.fieldMask[k / 16][k % 5] |= uint16_t(1u << (k % 16));
        }
        return tables;
    }();
    const __m512i fields[5] = {_mm512_castps_si512(t.m), _mm512_castps_si512(u.m), _mm512_castps_si512(v.m),
                               primId.m, geomId.m};
    int32_t* dwords = reinterpret_cast<int32_t*>(out);
    const int total = 5 * count;
    for (int s = 0; s < 5 && 16 * s < total; ++s) {
        const __m512i lanes = _mm512_loadu_si512(kTables.lane[s]);
        __m512i x = _mm512_setzero_si512();
        for (int f = 0; f < 5; ++f) x = _mm512_mask_permutexvar_epi32(x, kTables.fieldMask[s][f], lanes, fields[f]);
        const int left = total - 16 * s;
        if (left >= 16) _mm512_storeu_si512(dwords + 16 * s, x);
        else _mm512_mask_storeu_epi32(dwords + 16 * s, __mmask16((1u << left) - 1), x);
    }
}
#endif

/// The hits (or occlusion) of a packet, written out: invalid lanes miss and are not occluded.
template <int K, bool AnyHit, class UserHits>
inline void writePacketResults(const PacketHit<K>& h, const UserHits& user, uint32_t validBits, uint32_t occludedBits,
                               int count, Hit* hitsOut, uint8_t* occludedOut) {
    if constexpr (AnyHit) {
        for (int lane = 0; lane < count; ++lane) occludedOut[lane] = (validBits & occludedBits) >> lane & 1;
        return;
    }
    // Triangle hits and misses without branches (they interleave unpredictably at silhouettes); the
    // rare user-primitive hits are patched after.
    const uint32_t triangleBits = validBits & ~movemask(h.primId == vint<K>(kNoPrim));
    uint32_t userBits = 0;
#if defined(__AVX512F__)
    if constexpr (K == 16) {
        const vbool16 triangle = maskFromBits16(triangleBits);
        const vfloat16 zero(0.0f);
        const vint16 invalid = vint16(int32_t(kInvalidId));
        storeHits16(select(triangle, h.t, vfloat16(__builtin_huge_valf())), select(triangle, h.u, zero),
                    select(triangle, h.v, zero), select(triangle, h.primId, invalid), select(triangle, vint16(0), invalid),
                    count, hitsOut);
        for (uint32_t bits = validBits & ~triangleBits; bits; bits &= bits - 1) {
            const int lane = __builtin_ctz(bits);
            userBits |= uint32_t(user.geomId(lane) != kInvalidId) << lane;
        }
    } else
#endif
    {
        PacketLanes<K> lanes;
        lanes.store(h);
        for (int lane = 0; lane < count; ++lane) {
            const bool triangle = triangleBits >> lane & 1;
            Hit& out = hitsOut[lane];
            out.t = triangle ? lanes.t[lane] : __builtin_huge_valf();
            out.u = triangle ? lanes.u[lane] : 0.0f;
            out.v = triangle ? lanes.v[lane] : 0.0f;
            out.primId = triangle ? uint32_t(lanes.prim[lane]) : kInvalidId;
            out.geomId = triangle ? 0 : kInvalidId;
            userBits |= uint32_t(!triangle && user.geomId(lane) != kInvalidId) << lane;
        }
        userBits &= validBits;
    }
    if (!userBits) return;
    PacketLanes<K> lanes;
    lanes.store(h);
    for (; userBits; userBits &= userBits - 1) {
        const int lane = __builtin_ctz(userBits);
        hitsOut[lane] = laneHit(lanes, user, lane);
    }
}

/// Traces a loaded packet of K rays (`rays` its rays) from the root, starting from its state as it
/// stands: `h` the hits so far (closest hit), `done` the lanes whose answer is known (any-hit: invalid
/// or occluded). A packet that already found hits culls by them and ends with the reference's
/// answer all the same. At most K / 4 active rays finish a subtree one by one, and with `partSingly`
/// the rays of an incoherent packet (closest hit) from the first node where they part. Returns
/// whether the packet was incoherent (too spread for interval culling). Any-hit packets write the
/// block that last occluded one of their rays to `lastOccluder`, where given. Inlined, so that the
/// packet's hits stay in registers.
template <int N, int K, bool AnyHit, class Leaves, class Cost>
[[gnu::always_inline]] inline bool traversePacket(const SceneView<N>& scene, const Ray* rays, const PacketRay<K>& p,
                                                  PacketHit<K>& h, PacketUserHits<K>& user, vbool<K>& done,
                                                  bool partSingly, Cost& cost, uint32_t* lastOccluder = nullptr) {
    using F = vfloat<K>;
    constexpr int switchToSingle = K / 4;
    const Leaves leaves{scene.leaves, lastOccluder};
    const F inf(__builtin_huge_valf());
    const vbool<K> valid = andNot(vbool<K>(true), done);

    // A subtree waits on the stack with the rays that enter its box, and (closest hit) the nearest of
    // their entries, or the interval's entry, which is below each of theirs: when it is popped, the
    // rays whose hits are nearer than that bound cannot find a nearer one there. (Any-hit rays keep
    // their tfar until they are done.) Each ray's own entry, kept instead, culls a few more rays at
    // the cost of a K-wide entry on the stack (docs/performance-analysis.md, session 28).
    struct Entry {
        uint32_t lanes;  ///< the rays that enter
        NodeRef ref;
        float distance;  ///< closest hit: the stack's order, and the bound its rays are culled by
    };
    Entry stack[kStackSize<N>];
    int sp = 0;
    if (any(valid)) stack[sp++] = {movemask(valid), scene.root, -__builtin_huge_valf()};
    // A coherent packet first tests each node's children by its rays' interval, and each ray only
    // against the children that the interval enters (as Embree's coherent packets do): the per-ray
    // results are the same, with fewer per-ray tests.
    RayInterval interval{};
    bool byInterval = false;
    if (p.uniformOctant && any(valid)) {
        RayBounds<K> bounds;
        bounds.add(p, valid);
        interval = bounds.interval(p);
        byInterval = narrowEnough(interval);
    }
    // Any-hit rays keep their tfar until they are done, so the interval also culls the children that
    // lie beyond the farthest of them (shadow rays stop at the light).
    const float intervalTfar = AnyHit && byInterval ? reduceMax(select(valid, h.t, -inf)) : __builtin_huge_valf();
    // The rays in `bits` finish the subtree at `ref` one by one.
    auto finishSingly = [&](NodeRef ref, uint32_t bits) {
        PacketLanes<K> lanes;
        lanes.store(h);
        for (; bits; bits &= bits - 1) {
            const int lane = __builtin_ctz(bits);
            Hit hit = laneHit(lanes, user, lane);
            TraversalCost laneCost;
            const SingleRayState s = laneState(p, lane);
            const bool occluded = traceSubtree<N, kNodeSimdWidth<N>, kBlockSize, AnyHit, Leaves, Cost::counting>(
                scene, ref, rays[lane], s.box, [&] { return s.woop; }, hit, laneCost, lastOccluder);
            cost.add(lane, laneCost);
            if (occluded) {
                lanes.t[lane] = -__builtin_huge_valf();
                lanes.prim[lane] = 0;
            } else {
                setLaneHit(lanes, user, lane, hit);
            }
        }
        lanes.load(h);
        if constexpr (AnyHit) done |= h.t == F(-__builtin_huge_valf());
    };
    while (sp > 0) {
        Entry e = stack[--sp];
        vbool<K> active;
        if constexpr (AnyHit) active = maskFromBits<K>(e.lanes & ~movemask(done));
        else active = maskFromBits<K>(e.lanes) & (F(e.distance) <= h.t * F(kRobustFarScale));
        const uint32_t activeBits = movemask(active);
        if (!activeBits) continue;
        if (__builtin_popcount(activeBits) <= switchToSingle) {
            finishSingly(e.ref, activeBits);
            continue;
        }

        NodeRef ref = e.ref;
        while (!ref.isLeaf()) {
            const WideNode<N>& node = scene.nodes[ref.index()];
            cost.visit(movemask(active));
            // Continue with the child entered first (by the nearest ray, or by the interval); push the
            // others sorted by that entry, farthest first (any-hit: any occluder will do, so no order
            // is kept).
            // The nearest so far waits in registers rather than on the stack.
            Entry nearest{};
            bool found = false;
            const int base = sp;
            uint32_t candidates = (1u << N) - 1;
            alignas(64) float intervalEntry[N];
            if (byInterval) {
                candidates = intersectChildrenInterval<N>(node, interval, intervalTfar, intervalEntry);
            }
            for (; candidates; candidates &= candidates - 1) {
                const int i = __builtin_ctz(candidates);
                if (node.child[i].bits == NodeRef::empty().bits) continue;
                const F entry = packetChildEntry<N, K>(node, i, p, h.t, active);
                if (none(entry < inf)) continue;
                prefetchChild(scene, node.child[i]);
                // Ordered by the interval's entry where there is one (a bound on the rays' entries,
                // without a horizontal minimum per child).
                float distance = 0.0f;
                if constexpr (!AnyHit) distance = byInterval ? intervalEntry[i] : reduceMin(entry);
                const Entry e{movemask(entry < inf), node.child[i], distance};
                if (!found) {
                    nearest = e;
                    found = true;
                } else if (!AnyHit && e.distance < nearest.distance) {
                    pushSorted(stack, base, sp, nearest);
                    nearest = e;
                } else if constexpr (AnyHit) {
                    stack[sp++] = e;
                } else {
                    pushSorted(stack, base, sp, e);
                }
            }
            if (!found) goto pop;
            // An incoherent packet that parts here would visit the children in one order for all of
            // its rays, mostly not theirs (rays that start on surfaces start inside several boxes, and
            // a far child visited first finds hits the near one would have culled): where partSingly,
            // its rays go on one by one from here, each in its own order.
            if constexpr (!AnyHit)
                if (partSingly && !byInterval && sp > base) {
                    uint32_t entered = nearest.lanes;
                    for (int k = base; k < sp; ++k) entered |= stack[k].lanes;
                    sp = base;
                    finishSingly(ref, entered);
                    goto pop;
                }
            ref = nearest.ref;
            active = maskFromBits<K>(nearest.lanes);
        }
        {
            const vbool<K> occluded = leaves.template packet<K, AnyHit>(ref, p, active, h, user, cost);
            if constexpr (AnyHit) {
                done |= occluded;
                if (all(done)) sp = 0;  // every ray is answered
            }
        }
    pop:;
    }
    return !byInterval;
}

/// Any-hit with a shadow cache: the lanes that the cached blocks occlude are done before the
/// traversal (whose occluder the caller then caches). A block that occludes none of the packet's
/// rays left is dropped, so that where the cache does not pay (rays toward several lights
/// interleaved, unshadowed regions), packets stop testing it until a traversal finds an occluder.
template <int K>
[[gnu::always_inline]] inline void occludeByCache(const SceneLeaves& leaves, ShadowCache& cache, const PacketRay<K>& p,
                                                  PacketHit<K>& h, vbool<K>& done) {
    vbool<K> active = andNot(vbool<K>(true), done);
    cache.queries += uint32_t(__builtin_popcount(movemask(active)));
    for (int entry = 0; entry < ShadowCache::kBlocks && cache.blocks[entry] != ShadowCache::kEmpty && any(active);) {
        const vbool<K> occluded = occludeByBlock(leaves.blocks[cache.blocks[entry]], p, active, h);
        if (none(occluded)) {
            cache.forget(entry);
            continue;
        }
        cache.hits += uint32_t(__builtin_popcount(movemask(occluded)));
        done |= occluded;
        active = andNot(active, occluded);
        ++entry;
    }
}

/// Closest hits (or occlusion, through `cache` where given) of up to K rays, and their costs with
/// `Counting`.
template <int N, int K, bool AnyHit, bool Counting, class Leaves>
inline void tracePacketCounted(const SceneView<N>& scene, const Ray* rays, int count, Hit* hitsOut,
                               uint8_t* occludedOut, TraversalCost* costsOut, IncoherentPackets* history,
                               ShadowCache* cache = nullptr) {
    using F = vfloat<K>;
    PacketRay<K> p;
    PacketHit<K> h;
    PacketUserHits<K> user(rays);
    PacketCost<K, Counting> cost;
    const vbool<K> valid = loadPacket(rays, count, p, h);
    vbool<K> done = andNot(vbool<K>(true), valid);
    const bool partSingly = !history || history->partSingly(p, valid);
    if (AnyHit && cache) occludeByCache(scene.leaves, *cache, p, h, done);
    const bool incoherent = traversePacket<N, K, AnyHit, Leaves>(scene, rays, p, h, user, done, partSingly, cost,
                                                                 cache ? &cache->found : nullptr);
    if (cache) cache->remember();
    if (!AnyHit && history && incoherent) {
        const vbool<K> hit = valid & (h.t < F(__builtin_huge_valf()));
        history->add(__builtin_popcount(movemask(valid)), __builtin_popcount(movemask(hit)));
    }
    writePacketResults<K, AnyHit>(h, user, movemask(valid), movemask(h.t == F(-__builtin_huge_valf())), count,
                                  hitsOut, occludedOut);
    cost.write(count, costsOut);
}

/// Closest hits (or occlusion) of up to K rays, and their costs where `costsOut` is given. `history`:
/// the incoherent packets traced before in the same batch, which decide partSingly (closest hit;
/// without one, incoherent packets part singly). `cache`: any-hit's shadow cache, where given.
template <int N, int K, bool AnyHit, class Leaves = SceneLeafIntersector<N>>
inline void tracePacket(const SceneView<N>& scene, const Ray* rays, int count, Hit* hitsOut, uint8_t* occludedOut,
                        TraversalCost* costsOut = nullptr, IncoherentPackets* history = nullptr,
                        ShadowCache* cache = nullptr) {
    if (costsOut)
        return tracePacketCounted<N, K, AnyHit, true, Leaves>(scene, rays, count, hitsOut, occludedOut, costsOut,
                                                              history, cache);
    tracePacketCounted<N, K, AnyHit, false, Leaves>(scene, rays, count, hitsOut, occludedOut, nullptr, history, cache);
}

} // namespace WIDERAY_ISA
} // namespace wideray
