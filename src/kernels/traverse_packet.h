#pragma once
// Packet traversal: K rays (a 2x2, 4x2 or 4x4 pixel block for K = 4, 8, 16) walk the wide BVH
// together. Each child box is tested against all active rays in one K-wide operation; a subtree is
// entered with the rays that hit its box, culled per ray against that ray's closest hit, and left
// to single-ray traversal once few rays remain active (Wald et al. 2001, "Interactive Rendering
// with Coherent Ray Tracing"; Embree's hybrid packet/single-ray scheme, Benthin et al. 2012).
// Triangle tests run the same watertight arithmetic per lane as the scalar reference, so results
// are bit-identical.
#include "kernels/traverse_single.h"

#include "simd/isa_namespace.h"

namespace wideray {
inline namespace WIDERAY_ISA {

template <int K>
struct PacketRay {
    vfloat<K> ox, oy, oz, rdx, rdy, rdz, tnear;
    vbool<K> negX, negY, negZ;
    WatertightRay<vfloat<K>, vint<K>> woop;
    // Coherent packets usually share the direction octant and the dominant axes; then planes and
    // vertex coordinates are picked once per packet instead of per lane (same arithmetic).
    bool uniformOctant = false, uniformAxes = false;
    bool negXs = false, negYs = false, negZs = false;
    int kx = 0, ky = 0, kz = 0;
    vfloat<K> okx, oky, okz;  ///< the origin permuted to (kx, ky, kz), when uniformAxes
};

/// Finds out whether the active lanes share the direction octant (see PacketRay).
template <int K>
inline void classifyOctant(PacketRay<K>& p, uint32_t lanes) {
    uint32_t nx = movemask(p.negX) & lanes, ny = movemask(p.negY) & lanes, nz = movemask(p.negZ) & lanes;
    p.uniformOctant = (nx == 0 || nx == lanes) && (ny == 0 || ny == lanes) && (nz == 0 || nz == lanes);
    p.negXs = nx != 0; p.negYs = ny != 0; p.negZs = nz != 0;
}

/// Finds out whether the active lanes share the watertight test's axes (see PacketRay).
template <int K>
inline void classifyAxes(PacketRay<K>& p, uint32_t lanes) {
    p.uniformAxes = false;
    if (!lanes) return;
    alignas(64) int32_t kx[K], ky[K], kz[K];
    p.woop.kx.store(kx); p.woop.ky.store(ky); p.woop.kz.store(kz);
    int first = __builtin_ctz(lanes);
    p.kx = kx[first]; p.ky = ky[first]; p.kz = kz[first];
    p.uniformAxes = true;
    for (uint32_t l = lanes; l; l &= l - 1) {
        int i = __builtin_ctz(l);
        p.uniformAxes = p.uniformAxes && kx[i] == p.kx && ky[i] == p.ky && kz[i] == p.kz;
    }
    if (p.uniformAxes) {
        const vfloat<K>* o[3] = {&p.ox, &p.oy, &p.oz};
        p.okx = *o[p.kx]; p.oky = *o[p.ky]; p.okz = *o[p.kz];
    }
}

/// Hits in SIMD registers; primId is INT32_MAX for "none yet" so that the tie rule is one compare.
template <int K>
struct PacketHit {
    vfloat<K> t, u, v;
    vint<K> primId;
};

constexpr int32_t kNoPrim = INT32_MAX;

/// Loads up to K rays; invalid and missing lanes get tnear = +inf, tfar = -inf and stay inactive.
template <int K>
inline vbool<K> loadPacket(const Ray* rays, int count, PacketRay<K>& p, PacketHit<K>& h) {
    using F = vfloat<K>;
    alignas(64) float ox[K], oy[K], oz[K], dx[K], dy[K], dz[K], tn[K], tf[K];
    for (int i = 0; i < K; ++i) {
        const Ray& r = rays[i < count ? i : 0];
        ox[i] = r.ox; oy[i] = r.oy; oz[i] = r.oz;
        dx[i] = r.dx; dy[i] = r.dy; dz[i] = r.dz;
        tn[i] = r.tnear; tf[i] = r.tfar;
    }
    alignas(64) static constexpr int32_t kLane[16] = {0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15};
    F Ox = F::load(ox), Oy = F::load(oy), Oz = F::load(oz), Dx = F::load(dx), Dy = F::load(dy), Dz = F::load(dz);
    F tnear = F::load(tn), tfar = F::load(tf);
    const F zero(0.0f), inf(__builtin_huge_valf());
    // isValidRay, lane by lane: finite origin and direction, a non-zero direction, tnear <= tfar.
    vbool<K> valid = (vint<K>::load(kLane) < vint<K>(count)) & isFinite(Ox) & isFinite(Oy) & isFinite(Oz) &
                     isFinite(Dx) & isFinite(Dy) & isFinite(Dz) &
                     andNot(vbool<K>(true), (Dx == zero) & (Dy == zero) & (Dz == zero)) & (tnear <= tfar) &
                     (tnear < inf);
    const F one(1.0f);
    Dx = select(valid, Dx, zero); Dy = select(valid, Dy, zero); Dz = select(valid, Dz, one);
    p.ox = select(valid, Ox, zero); p.oy = select(valid, Oy, zero); p.oz = select(valid, Oz, zero);
    p.rdx = one / Dx; p.rdy = one / Dy; p.rdz = one / Dz;
    p.negX = p.rdx < zero; p.negY = p.rdy < zero; p.negZ = p.rdz < zero;
    p.tnear = select(valid, tnear, inf);
    p.woop = makeWatertightRay<F, vint<K>>(p.ox, p.oy, p.oz, Dx, Dy, Dz);
    h.t = select(valid, tfar, -inf);
    h.u = h.v = zero;
    h.primId = vint<K>(kNoPrim);
    classifyOctant(p, movemask(valid));
    classifyAxes(p, movemask(valid));
    return valid;
}

/// Entry distances of the packet into child i of a node; +inf for rays that miss or are inactive.
template <int N, int K>
[[gnu::always_inline]] inline vfloat<K> packetChildEntry(const WideNode<N>& node, int i, const PacketRay<K>& p, const vfloat<K>& tfar,
                                  const vbool<K>& active) {
    using F = vfloat<K>;
    F nearX, farX, nearY, farY, nearZ, farZ;
    if (p.uniformOctant) {
        nearX = F(p.negXs ? node.upperX[i] : node.lowerX[i]); farX = F(p.negXs ? node.lowerX[i] : node.upperX[i]);
        nearY = F(p.negYs ? node.upperY[i] : node.lowerY[i]); farY = F(p.negYs ? node.lowerY[i] : node.upperY[i]);
        nearZ = F(p.negZs ? node.upperZ[i] : node.lowerZ[i]); farZ = F(p.negZs ? node.lowerZ[i] : node.upperZ[i]);
    } else {
        F lx(node.lowerX[i]), ux(node.upperX[i]), ly(node.lowerY[i]), uy(node.upperY[i]), lz(node.lowerZ[i]),
            uz(node.upperZ[i]);
        nearX = select(p.negX, ux, lx); farX = select(p.negX, lx, ux);
        nearY = select(p.negY, uy, ly); farY = select(p.negY, ly, uy);
        nearZ = select(p.negZ, uz, lz); farZ = select(p.negZ, lz, uz);
    }
    F tx0 = (nearX - p.ox) * p.rdx, tx1 = (farX - p.ox) * p.rdx;
    F ty0 = (nearY - p.oy) * p.rdy, ty1 = (farY - p.oy) * p.rdy;
    F tz0 = (nearZ - p.oz) * p.rdz, tz1 = (farZ - p.oz) * p.rdz;
    F tEntry = max(tx0, max(ty0, max(tz0, p.tnear)));
    F tExit = min(tx1, min(ty1, min(tz1, tfar))) * F(kRobustFarScale);
    return select(active & (tEntry <= tExit), tEntry, F(__builtin_huge_valf()));
}

/// All K rays against the triangles of one block. Returns the lanes that hit (for any-hit).
template <int K, bool AnyHit>
[[gnu::always_inline]] inline vbool<K> intersectBlockPacket(const TriangleBlock<kBlockSize>& block, const PacketRay<K>& p,
                                     vbool<K> active, PacketHit<K>& h) {
    using F = vfloat<K>;
    using I = vint<K>;
    vbool<K> anyHit(false);
    for (int j = 0; j < kBlockSize && block.primId[j] != kInvalidId; ++j) {
        F t = h.t, u = h.u, v = h.v;
        vbool<K> hit;
        if (p.uniformAxes) {
            const float v0[3] = {block.v0x[j], block.v0y[j], block.v0z[j]};
            const float v1[3] = {block.v1x[j], block.v1y[j], block.v1z[j]};
            const float v2[3] = {block.v2x[j], block.v2y[j], block.v2z[j]};
            hit = intersectWatertightPermuted(p.woop.sx, p.woop.sy, p.woop.sz, active, F(v0[p.kx]) - p.okx,
                                              F(v0[p.ky]) - p.oky, F(v0[p.kz]) - p.okz, F(v1[p.kx]) - p.okx,
                                              F(v1[p.ky]) - p.oky, F(v1[p.kz]) - p.okz, F(v2[p.kx]) - p.okx,
                                              F(v2[p.ky]) - p.oky, F(v2[p.kz]) - p.okz, p.tnear, h.t, t, u, v);
        } else {
            hit = intersectWatertight(p.woop, active, F(block.v0x[j]), F(block.v0y[j]), F(block.v0z[j]),
                                      F(block.v1x[j]), F(block.v1y[j]), F(block.v1z[j]), F(block.v2x[j]),
                                      F(block.v2y[j]), F(block.v2z[j]), p.tnear, h.t, t, u, v);
        }
        if (none(hit)) continue;
        if constexpr (AnyHit) {
            anyHit |= hit;
            active = andNot(active, hit);
            continue;
        }
        I prim(int32_t(block.primId[j]));
        vbool<K> closer = hit & ((t < h.t) | ((t == h.t) & (prim < h.primId)));
        h.t = select(closer, t, h.t);
        h.u = select(closer, u, h.u);
        h.v = select(closer, v, h.v);
        h.primId = select(closer, prim, h.primId);
    }
    return anyHit;
}

template <int K>
struct PacketLanes {
    alignas(64) float t[K], u[K], v[K];
    alignas(64) int32_t prim[K];

    void store(const PacketHit<K>& h) { h.t.store(t); h.u.store(u); h.v.store(v); h.primId.store(prim); }
    void load(PacketHit<K>& h) const {
        h.t = vfloat<K>::load(t); h.u = vfloat<K>::load(u); h.v = vfloat<K>::load(v); h.primId = vint<K>::load(prim);
    }
    Hit hit(int lane, uint32_t geomId) const {
        return prim[lane] == kNoPrim ? Hit{t[lane], 0, 0, kInvalidId, kInvalidId}
                                     : Hit{t[lane], u[lane], v[lane], uint32_t(prim[lane]), geomId};
    }
};

/// Closest hits (or occlusion) of up to K rays. `switchToSingle`: at most this many active rays
/// finish the subtree one by one.
template <int N, int K, bool AnyHit>
inline void tracePacket(const SceneView<N>& scene, const Ray* rays, int count, Hit* hitsOut, uint8_t* occludedOut) {
    using F = vfloat<K>;
    constexpr int switchToSingle = K / 4;
    PacketRay<K> p;
    PacketHit<K> h;
    const vbool<K> valid = loadPacket(rays, count, p, h);
    vbool<K> done = andNot(vbool<K>(true), valid);  // any-hit: lanes whose answer is known
    const TriangleBvhView<N>& tri = scene.triangles;
    const F inf(__builtin_huge_valf());

    if (tri.blocks && any(valid)) {
        struct alignas(64) Entry {
            F dist;
            NodeRef ref;
        };
        Entry stack[kStackSize<N>];
        int sp = 0;
        stack[sp++] = {select(valid, p.tnear, inf), tri.root};
        while (sp > 0) {
            Entry e = stack[--sp];
            vbool<K> active = e.dist <= h.t * F(kRobustFarScale);
            if constexpr (AnyHit) active = andNot(active, done);
            uint32_t activeBits = movemask(active);
            if (!activeBits) continue;
            if (__builtin_popcount(activeBits) <= switchToSingle) {
                PacketLanes<K> lanes;
                lanes.store(h);
                for (; activeBits; activeBits &= activeBits - 1) {
                    int lane = __builtin_ctz(activeBits);
                    const Ray& ray = rays[lane];
                    Hit hit = lanes.hit(lane, 0);
                    SingleRayState s = makeSingleRayState(ray);
                    bool occluded = false;
                    TraversalCost cost;
                    traverseWide<N, kNodeSimdWidth<N>>(
                        tri.nodes, e.ref, s.box, ray.tnear, [&] { return hit.t; },
                        [&](uint32_t first, uint32_t n) {
                            for (uint32_t b = first; b < first + n; ++b)
                                if (intersectBlock<kBlockSize, AnyHit>(tri.blocks[b], s, ray, hit)) return occluded = true;
                            return false;
                        },
                        cost);
                    if (AnyHit && occluded) {
                        lanes.t[lane] = -__builtin_huge_valf();
                        lanes.prim[lane] = 0;
                    } else if (hit.valid()) {
                        lanes.t[lane] = hit.t; lanes.u[lane] = hit.u; lanes.v[lane] = hit.v;
                        lanes.prim[lane] = int32_t(hit.primId);
                    }
                }
                lanes.load(h);
                if constexpr (AnyHit) done |= h.t == F(-__builtin_huge_valf());
                continue;
            }

            NodeRef ref = e.ref;
            while (!ref.isLeaf()) {
                const WideNode<N>& node = tri.nodes[ref.index()];
                // Insert the hit children into the stack sorted by their nearest ray's entry,
                // farthest first, then continue with the nearest (closest hit only).
                float order[N];
                const int base = sp;
                for (int i = 0; i < N; ++i) {
                    if (node.child[i].bits == NodeRef::empty().bits) continue;
                    F dist = packetChildEntry<N, K>(node, i, p, h.t, active);
                    if (none(dist < inf)) continue;
                    if constexpr (AnyHit) {  // any occluder will do: no order to keep
                        stack[sp++] = {dist, node.child[i]};
                        continue;
                    }
                    float key = reduceMin(dist);
                    int j = sp++;
                    for (; j > base && order[j - 1 - base] < key; --j) {
                        stack[j] = stack[j - 1];
                        order[j - base] = order[j - 1 - base];
                    }
                    stack[j] = {dist, node.child[i]};
                    order[j - base] = key;
                }
                if (sp == base) goto pop;
                --sp;
                ref = stack[sp].ref;
                active = stack[sp].dist < inf;
            }
            for (uint32_t b = ref.first(); b < ref.first() + ref.count(); ++b) {
                vbool<K> hit = intersectBlockPacket<K, AnyHit>(tri.blocks[b], p, active, h);
                if constexpr (AnyHit) {
                    done |= hit;
                    h.t = select(hit, F(-__builtin_huge_valf()), h.t);
                    active = andNot(active, hit);
                    if (all(done)) {
                        sp = 0;  // every ray is answered
                        break;
                    }
                }
            }
        pop:;
        }
    }

    PacketLanes<K> lanes;
    lanes.store(h);
    uint32_t validBits = movemask(valid);
    for (int lane = 0; lane < count; ++lane) {
        if (!(validBits >> lane & 1)) {
            if constexpr (AnyHit) occludedOut[lane] = 0;
            else hitsOut[lane] = Hit{};
            continue;
        }
        if constexpr (AnyHit) {
            bool occluded = lanes.t[lane] == -__builtin_huge_valf();
            if (!occluded && scene.user.prims) {
                Hit hit;
                hit.t = rays[lane].tfar;
                TraversalCost cost;
                occluded = traceUser<N, kNodeSimdWidth<N>, true>(scene.user, rays[lane], makeSingleRayState(rays[lane]), hit, cost);
            }
            occludedOut[lane] = occluded ? 1 : 0;
        } else {
            Hit hit = lanes.hit(lane, 0);
            if (scene.user.prims) {
                TraversalCost cost;
                traceUser<N, kNodeSimdWidth<N>, false>(scene.user, rays[lane], makeSingleRayState(rays[lane]), hit, cost);
            }
            hitsOut[lane] = hit.valid() ? hit : Hit{};
        }
    }
}

} // namespace WIDERAY_ISA
} // namespace wideray
