#pragma once
// Ray stream traversal for incoherent rays (after Barringer and Akenine-Moller 2014, "Dynamic Ray
// Stream Traversal", and Wald et al. 2014, "Embree"). A stream of up to a few thousand rays is
// sorted (direction octant, then a Morton code of the origin) and stored as structure of arrays.
// It then walks the BVH as a list of ray indices: at each inner node the list is filtered against
// every child box, K rays per SIMD test, into one list per child; leaves test K rays per triangle.
// Each ray is culled against its own closest hit. Children are visited in the order of the nearest
// entry among their rays. Triangle arithmetic is the reference's, lane by lane.
#include "kernels/stream_workspace.h"
#include "kernels/traverse_packet.h"

#include "simd/isa_namespace.h"

namespace wideray {
inline namespace WIDERAY_ISA {

inline uint32_t spreadBits10(uint32_t x) {
    x &= 0x3FF;
    x = (x | (x << 16)) & 0x030000FF;
    x = (x | (x << 8)) & 0x0300F00F;
    x = (x | (x << 4)) & 0x030C30C3;
    x = (x | (x << 2)) & 0x09249249;
    return x;
}

/// Fills the workspace with the valid rays, sorted; returns how many there are.
template <int K>
inline size_t loadStream(const Ray* rays, size_t count, StreamWorkspace& ws) {
    ws.reserveRays(count);
    float lo[3] = {__builtin_huge_valf(), __builtin_huge_valf(), __builtin_huge_valf()};
    float hi[3] = {-__builtin_huge_valf(), -__builtin_huge_valf(), -__builtin_huge_valf()};
    for (size_t i = 0; i < count; ++i) {
        ws.valid[i] = isValidRay(rays[i]);
        if (!ws.valid[i]) continue;
        const float o[3] = {rays[i].ox, rays[i].oy, rays[i].oz};
        for (int a = 0; a < 3; ++a) {
            lo[a] = min(lo[a], o[a]);
            hi[a] = max(hi[a], o[a]);
        }
    }
    float scale[3];
    for (int a = 0; a < 3; ++a) scale[a] = 1023.0f / max(hi[a] - lo[a], 1e-30f);
    size_t n = 0;
    for (size_t i = 0; i < count; ++i) {
        if (!ws.valid[i]) continue;
        const Ray& r = rays[i];
        uint32_t octant = (r.dx < 0.0f ? 1u : 0u) | (r.dy < 0.0f ? 2u : 0u) | (r.dz < 0.0f ? 4u : 0u);
        uint32_t morton = spreadBits10(uint32_t((r.ox - lo[0]) * scale[0])) |
                          (spreadBits10(uint32_t((r.oy - lo[1]) * scale[1])) << 1) |
                          (spreadBits10(uint32_t((r.oz - lo[2]) * scale[2])) << 2);
        ws.keys[n++] = (uint64_t(octant << 30 | morton) << 32) | i;
    }
    sortStreamKeys(ws.keys, n);
    // Set up K rays at a time with the packet code (same arithmetic as every other kernel).
    for (size_t s = 0; s < n; s += K) {
        alignas(64) float ox[K], oy[K], oz[K], dx[K], dy[K], dz[K];
        const int count = int(n - s < size_t(K) ? n - s : size_t(K));
        for (int l = 0; l < K; ++l) {
            const Ray& r = rays[uint32_t(ws.keys[s + (l < count ? l : 0)])];
            ox[l] = r.ox; oy[l] = r.oy; oz[l] = r.oz;
            dx[l] = r.dx; dy[l] = r.dy; dz[l] = r.dz;
        }
        using F = vfloat<K>;
        F Ox = F::load(ox), Oy = F::load(oy), Oz = F::load(oz), Dx = F::load(dx), Dy = F::load(dy), Dz = F::load(dz);
        auto woop = makeWatertightRay<F, vint<K>>(Ox, Oy, Oz, Dx, Dy, Dz);
        // The arrays have room for whole vectors (capacity is a multiple of 16).
        Ox.store(ws.ox + s); Oy.store(ws.oy + s); Oz.store(ws.oz + s);
        (F(1.0f) / Dx).store(ws.rdx + s); (F(1.0f) / Dy).store(ws.rdy + s); (F(1.0f) / Dz).store(ws.rdz + s);
        woop.kx.store(ws.kx + s); woop.ky.store(ws.ky + s); woop.kz.store(ws.kz + s);
        woop.sx.store(ws.sx + s); woop.sy.store(ws.sy + s); woop.sz.store(ws.sz + s);
        F(0.0f).store(ws.u + s); F(0.0f).store(ws.v + s);
        vint<K>(kNoPrim).store(ws.prim + s);
        for (int l = 0; l < count; ++l) {
            uint32_t i = uint32_t(ws.keys[s + l]);
            ws.rayOf[s + l] = i;
            ws.tnear[s + l] = rays[i].tnear;
            ws.tfar[s + l] = rays[i].tfar;
        }
    }
    return n;
}

/// The rays of list[0..K) (fewer at the end: `valid` marks the real ones) gathered into a packet.
template <int K>
inline void gatherPacket(const StreamWorkspace& ws, const vint<K>& idx, PacketRay<K>& p, PacketHit<K>& h) {
    using F = vfloat<K>;
    p.ox = gather(ws.ox, idx); p.oy = gather(ws.oy, idx); p.oz = gather(ws.oz, idx);
    p.rdx = gather(ws.rdx, idx); p.rdy = gather(ws.rdy, idx); p.rdz = gather(ws.rdz, idx);
    p.negX = p.rdx < F(0.0f); p.negY = p.rdy < F(0.0f); p.negZ = p.rdz < F(0.0f);
    p.tnear = gather(ws.tnear, idx);
    h.t = gather(ws.tfar, idx);
}

template <int K>
inline void gatherWoop(const StreamWorkspace& ws, const vint<K>& idx, PacketRay<K>& p, PacketHit<K>& h) {
    p.woop.ox = p.ox; p.woop.oy = p.oy; p.woop.oz = p.oz;
    p.woop.kx = gather(ws.kx, idx); p.woop.ky = gather(ws.ky, idx); p.woop.kz = gather(ws.kz, idx);
    p.woop.sx = gather(ws.sx, idx); p.woop.sy = gather(ws.sy, idx); p.woop.sz = gather(ws.sz, idx);
    h.u = gather(ws.u, idx); h.v = gather(ws.v, idx);
    h.primId = gather(ws.prim, idx);
}

template <int K>
inline void scatterHits(StreamWorkspace& ws, const vint<K>& idx, const PacketHit<K>& h, uint32_t lanes) {
    alignas(64) int32_t i[K], prim[K];
    alignas(64) float t[K], u[K], v[K];
    idx.store(i); h.primId.store(prim); h.t.store(t); h.u.store(u); h.v.store(v);
    for (; lanes; lanes &= lanes - 1) {
        int l = __builtin_ctz(lanes);
        ws.tfar[i[l]] = t[l]; ws.u[i[l]] = u[l]; ws.v[i[l]] = v[l]; ws.prim[i[l]] = prim[l];
    }
}

/// Loads K indices of a list that has `count` left; lanes past its end are not valid.
template <int K>
inline vint<K> loadIndices(const int32_t* list, size_t count, vbool<K>& valid) {
    alignas(64) static constexpr int32_t kLane[16] = {0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15};
    valid = vint<K>::load(kLane) < vint<K>(int32_t(count < size_t(K) ? count : size_t(K)));
    return select(valid, vint<K>::loadu(list), vint<K>(list[0]));
}

template <int N, int K, bool AnyHit>
inline void traceStreamTriangles(const TriangleBvhView<N>& tri, size_t n, StreamWorkspace& ws) {
    using F = vfloat<K>;
    const F inf(__builtin_huge_valf());
    struct Entry {
        NodeRef ref;
        uint32_t begin, end, restoreTop;
    };
    Entry stack[kStackSize<N>];
    int sp = 0;
    ws.reserveArena(n + K);
    for (size_t i = 0; i < n; ++i) ws.arena[i] = int32_t(i);
    stack[sp++] = {tri.root, 0, uint32_t(n), uint32_t(n)};
    while (sp > 0) {
        Entry e = stack[--sp];
        uint32_t top = e.restoreTop;
        if (e.ref.isLeaf()) {
            for (uint32_t at = e.begin; at < e.end; at += K) {
                vbool<K> valid;
                vint<K> idx = loadIndices<K>(&ws.arena[at], e.end - at, valid);
                PacketRay<K> p;
                PacketHit<K> h;
                gatherPacket(ws, idx, p, h);
                gatherWoop(ws, idx, p, h);
                vbool<K> active = valid & (p.tnear <= h.t);
                if (none(active)) continue;
                classifyAxes(p, movemask(active));
                for (uint32_t b = e.ref.first(); b < e.ref.first() + e.ref.count(); ++b) {
                    vbool<K> hit = intersectBlockPacket<K, AnyHit>(tri.blocks[b], p, active, h);
                    if constexpr (AnyHit) {
                        h.t = select(hit, F(-__builtin_huge_valf()), h.t);
                        active = andNot(active, hit);
                    }
                }
                scatterHits<K>(ws, idx, h, movemask(valid));
            }
            continue;
        }
        // Filter the list against all children at once: each child gets a region of the arena as
        // large as the list (plus K of slack for the vector loads of the next level).
        const WideNode<N>& node = tri.nodes[e.ref.index()];
        const uint32_t count = e.end - e.begin, region = count + K;
        int live[N], liveCount = 0;
        for (int i = 0; i < N; ++i)
            if (node.child[i].bits != NodeRef::empty().bits) live[liveCount++] = i;
        ws.reserveArena(top + liveCount * region + K);
        uint32_t childEnd[N];
        F closest[N];
        for (int c = 0; c < liveCount; ++c) {
            childEnd[c] = top + c * region;
            closest[c] = inf;
        }
        for (uint32_t at = e.begin; at < e.end; at += K) {
            vbool<K> valid;
            vint<K> idx = loadIndices<K>(&ws.arena[at], e.end - at, valid);
            PacketRay<K> p;
            PacketHit<K> h;
            gatherPacket(ws, idx, p, h);
            vbool<K> active = valid & (p.tnear <= h.t);
            classifyOctant(p, movemask(active));
            for (int c = 0; c < liveCount; ++c) {
                F dist = packetChildEntry<N, K>(node, live[c], p, h.t, active);
                closest[c] = min(closest[c], dist);
                childEnd[c] += uint32_t(compressStore(&ws.arena[childEnd[c]], idx, dist < inf));
            }
        }
        // Sorted insert: farthest first, so that the nearest child is popped first.
        Entry children[N];
        float nearest[N];
        int childCount = 0;
        for (int c = 0; c < liveCount; ++c) {
            uint32_t begin = top + c * region;
            if (childEnd[c] == begin) continue;
            float key = reduceMin(closest[c]);
            int j = childCount++;
            for (; j > 0 && nearest[j - 1] < key; --j) {
                children[j] = children[j - 1];
                nearest[j] = nearest[j - 1];
            }
            children[j] = {node.child[live[c]], begin, childEnd[c], 0};
            nearest[j] = key;
        }
        const uint32_t newTop = top + liveCount * region;
        for (int c = 0; c < childCount; ++c) {
            children[c].restoreTop = newTop;
            stack[sp++] = children[c];
        }
    }
}

/// Closest hits (AnyHit = false) or occlusion of `count` rays as one stream.
template <int N, int K, bool AnyHit>
inline void traceStream(const SceneView<N>& scene, const Ray* rays, size_t count, Hit* hitsOut, uint8_t* occludedOut,
                        StreamWorkspace& ws) {
    for (size_t i = 0; i < count; ++i) {
        if constexpr (AnyHit) occludedOut[i] = 0;
        else hitsOut[i] = Hit{};
    }
    size_t n = loadStream<K>(rays, count, ws);
    if (n == 0) return;
    if (scene.triangles.blocks) traceStreamTriangles<N, K, AnyHit>(scene.triangles, n, ws);
    for (size_t s = 0; s < n; ++s) {
        uint32_t i = ws.rayOf[s];
        const Ray& ray = rays[i];
        if constexpr (AnyHit) {
            bool occluded = ws.tfar[s] == -__builtin_huge_valf();
            if (!occluded && scene.user.prims) {
                Hit hit;
                hit.t = ray.tfar;
                TraversalCost cost;
                occluded = traceUser<N, kNodeSimdWidth<N>, true>(scene.user, ray, makeSingleRayState(ray), hit, cost);
            }
            occludedOut[i] = occluded ? 1 : 0;
        } else {
            Hit hit = ws.prim[s] == kNoPrim ? Hit{ws.tfar[s], 0, 0, kInvalidId, kInvalidId}
                                            : Hit{ws.tfar[s], ws.u[s], ws.v[s], uint32_t(ws.prim[s]), 0};
            if (scene.user.prims) {
                TraversalCost cost;
                traceUser<N, kNodeSimdWidth<N>, false>(scene.user, ray, makeSingleRayState(ray), hit, cost);
            }
            hitsOut[i] = hit.valid() ? hit : Hit{};
        }
    }
}

} // namespace WIDERAY_ISA
} // namespace wideray
