#pragma once
// Ray stream traversal for incoherent rays (after Barringer and Akenine-Moller 2014, "Dynamic Ray
// Stream Traversal", and Wald et al. 2014, "Embree"). A stream of up to a few thousand rays is
// sorted (direction octant, then a Morton code of the origin) and stored as structure of arrays.
// It then walks the BVH as a list of ray indices: at each inner node the list is filtered against
// every child box, K rays per SIMD test, into lists for the children; leaves test K rays per
// triangle. Each ray is culled against its own closest hit. Two orders (StreamOrder): one list per
// child, children in the order of their nearest ray, or each ray in its own nearest-first order as
// in Dynamic Ray Stream Traversal, which splits the lists finer. Near the leaves the lists get too
// short to fill a vector; there the rays finish the subtree as single rays taking turns
// (the hybrid of Benthin, Wald, Woop, Ernst and Mark 2012, "Combining Single and Packet-Ray Tracing
// for Arbitrary Ray Distributions on the Intel MIC Architecture", applied to streams). Triangle
// arithmetic is the reference's, lane by lane or ray by ray.
#include "kernels/stream_workspace.h"
#include "kernels/traverse_interleaved.h"
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

/// Fills the workspace with the valid rays (count < 2^kKeyIndexBits), sorted; returns how many there are.
template <int K>
inline size_t loadStream(const Ray* rays, size_t count, StreamWorkspace& ws) {
    constexpr uint64_t kIndexMask = (uint64_t(1) << kKeyIndexBits) - 1;
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
        ws.keys[n++] = uint64_t(octant) << 61 | uint64_t(morton) << kKeyIndexBits | i;
    }
    ws.sortKeys(n);
    // Set up K rays at a time with the packet code (same arithmetic as every other kernel).
    for (size_t s = 0; s < n; s += K) {
        const int count = int(n - s < size_t(K) ? n - s : size_t(K));
        using F = vfloat<K>;
        F fields[8];
        loadRayFields<K>([&](int l) -> const Ray& { return rays[uint32_t(ws.keys[s + (l < count ? l : 0)] & kIndexMask)]; }, fields);
        F Ox = fields[0], Oy = fields[1], Oz = fields[2], Dx = fields[3], Dy = fields[4], Dz = fields[5];
        auto woop = makeWatertightRay<F, vint<K>>(Ox, Oy, Oz, Dx, Dy, Dz);
        // The arrays have room for whole vectors (capacity is a multiple of 16).
        Ox.store(ws.ox + s); Oy.store(ws.oy + s); Oz.store(ws.oz + s);
        (F(1.0f) / Dx).store(ws.rdx + s); (F(1.0f) / Dy).store(ws.rdy + s); (F(1.0f) / Dz).store(ws.rdz + s);
        woop.kx.store(ws.kx + s); woop.ky.store(ws.ky + s); woop.kz.store(ws.kz + s);
        woop.sx.store(ws.sx + s); woop.sy.store(ws.sy + s); woop.sz.store(ws.sz + s);
        F(0.0f).store(ws.u + s); F(0.0f).store(ws.v + s);
        vint<K>(kNoPrim).store(ws.prim + s);
        for (int l = 0; l < count; ++l) {
            uint32_t i = uint32_t(ws.keys[s + l] & kIndexMask);
            ws.rayOf[s + l] = i;
            ws.userGeomId[s + l] = ws.userPrimId[s + l] = kInvalidId;
            ws.tnear[s + l] = rays[i].tnear;
            ws.tfar[s + l] = rays[i].tfar;
        }
    }
    return n;
}

/// K entries of a list of ray indices (fewer at its end: `valid` marks the real ones).
template <int K>
struct ListChunk {
    vint<K> idx;
    vbool<K> valid;
    int32_t first;
    bool contiguous;  ///< idx = first, first + 1, ...: the rays' data is read by plain loads

    vfloat<K> fetch(const float* array) const {
        return contiguous ? vfloat<K>::loadu(array + first) : gather(array, idx);
    }
    vint<K> fetch(const int32_t* array) const {
        return contiguous ? vint<K>::loadu(array + first) : gather(array, idx);
    }
};

/// Loads K entries of a list that has `count` left. Lists are strictly increasing (they are made
/// by scanning their parent list in order), so a run of K consecutive indices is told by its ends.
template <int K>
inline ListChunk<K> loadChunk(const int32_t* list, size_t count) {
    alignas(64) static constexpr int32_t kLane[16] = {0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15};
    ListChunk<K> c;
    c.valid = vint<K>::load(kLane) < vint<K>(int32_t(count < size_t(K) ? count : size_t(K)));
    c.idx = select(c.valid, vint<K>::loadu(list), vint<K>(list[0]));
    c.first = list[0];
    c.contiguous = count >= size_t(K) && list[K - 1] - list[0] == K - 1;
    return c;
}

/// The rays of a chunk as a packet, for box tests.
template <int K>
inline void gatherPacket(const StreamWorkspace& ws, const ListChunk<K>& c, PacketRay<K>& p, PacketHit<K>& h) {
    using F = vfloat<K>;
    p.ox = c.fetch(ws.ox); p.oy = c.fetch(ws.oy); p.oz = c.fetch(ws.oz);
    // The slab constants are remade from the origin and reciprocal (12 operations) rather than kept
    // per ray: that would be six more arrays to gather per chunk and node instead of three.
    p.slab = makeSlabRay(p.ox, p.oy, p.oz, c.fetch(ws.rdx), c.fetch(ws.rdy), c.fetch(ws.rdz));
    p.negX = p.slab.rdx < F(0.0f); p.negY = p.slab.rdy < F(0.0f); p.negZ = p.slab.rdz < F(0.0f);
    p.tnear = c.fetch(ws.tnear);
    h.t = c.fetch(ws.tfar);
}

/// The rest of what the triangle test needs.
template <int K>
inline void gatherWoop(const StreamWorkspace& ws, const ListChunk<K>& c, PacketRay<K>& p, PacketHit<K>& h) {
    p.woop.ox = p.ox; p.woop.oy = p.oy; p.woop.oz = p.oz;
    p.woop.kx = c.fetch(ws.kx); p.woop.ky = c.fetch(ws.ky); p.woop.kz = c.fetch(ws.kz);
    p.woop.sx = c.fetch(ws.sx); p.woop.sy = c.fetch(ws.sy); p.woop.sz = c.fetch(ws.sz);
    h.u = c.fetch(ws.u); h.v = c.fetch(ws.v);
    h.primId = c.fetch(ws.prim);
}

/// What the workspace keeps per stream slot for the rays of a chunk, lane by lane: the ids of hits on
/// user primitives (PacketUserHits' interface) and the traversal work (PacketCost's).
template <int K>
struct StreamLanes {
    const Ray* rays;  ///< the caller's array
    StreamWorkspace& ws;
    alignas(64) int32_t slot[K];

    StreamLanes(const Ray* callerRays, StreamWorkspace& workspace, const vint<K>& slots)
        : rays(callerRays), ws(workspace) {
        slots.store(slot);
    }
    const Ray& ray(int lane) const { return rays[ws.rayOf[slot[lane]]]; }
    uint32_t& geomId(int lane) const { return ws.userGeomId[slot[lane]]; }
    uint32_t& primId(int lane) const { return ws.userPrimId[slot[lane]]; }

    void visit(uint32_t lanes) {
        if (ws.countCost)
            for (; lanes; lanes &= lanes - 1) ++ws.costNodes[slot[__builtin_ctz(lanes)]];
    }
    void enter(uint32_t lanes) {
        if (ws.countCost)
            for (; lanes; lanes &= lanes - 1) ++ws.costLeaves[slot[__builtin_ctz(lanes)]];
    }
    void test(uint32_t lanes, uint32_t count) {
        if (ws.countCost)
            for (; lanes; lanes &= lanes - 1) ws.costPrimitives[slot[__builtin_ctz(lanes)]] += count;
    }
    void add(int lane, const TraversalCost& c) {
        if (!ws.countCost) return;
        ws.costNodes[slot[lane]] += c.nodes;
        ws.costLeaves[slot[lane]] += c.leaves;
        ws.costPrimitives[slot[lane]] += c.primitives;
    }
};

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

/// How the lists of a node's children are made and ordered.
enum class StreamOrder {
    ByList,  ///< one list per child; nearest entry first, ties to the child most rays enter first
    ByRay,   ///< Dynamic Ray Stream Traversal: every ray visits its children in its own nearest-first order
};

/// A list of rays waiting on the traversal stack for a node.
struct StreamEntry {
    NodeRef ref;
    uint32_t begin, end;  ///< the list in the arena (arenaEntry: where each ray enters the node)
    uint32_t restoreTop;  ///< the arena's top once the list is taken off the stack
    bool afterSibling;    ///< its rays come from a sibling visited first, which may have found hits nearer than this node
};

/// A node pushes at most N * N lists (ByRay: child x rank).
template <int N>
constexpr int kStreamStackSize = kMaxBvhDepth * N * N + 1;

/// The rays of a leaf's list against its primitives, K at a time.
template <int K, bool AnyHit, class Leaves>
inline void traceStreamLeaf(const Leaves& leaves, const Ray* rays, const StreamEntry& e, StreamWorkspace& ws) {
    for (uint32_t at = e.begin; at < e.end; at += K) {
        const ListChunk<K> chunk = loadChunk<K>(&ws.arena[at], e.end - at);
        PacketRay<K> p;
        PacketHit<K> h;
        gatherPacket(ws, chunk, p, h);
        const vbool<K> active = chunk.valid & (p.tnear <= h.t);
        if (none(active)) continue;
        gatherWoop(ws, chunk, p, h);
        if (!e.ref.isUserLeaf()) classifyAxes(p, movemask(active));
        StreamLanes<K> lanes(rays, ws, chunk.idx);
        leaves.template packet<K, AnyHit>(e.ref, p, active, h, lanes, lanes);
        scatterHits<K>(ws, chunk.idx, h, movemask(chunk.valid));
    }
}

/// The children of an inner node that exist, as slots.
template <int N>
inline int liveChildren(const WideNode<N>& node, int live[N]) {
    int count = 0;
    for (int i = 0; i < N; ++i)
        if (node.child[i].bits != NodeRef::empty().bits) live[count++] = i;
    return count;
}

/// Entry distances of the rays of a chunk into the node's live children (+inf: not entered).
template <int N, int K>
inline void childEntries(const WideNode<N>& node, const int* live, int liveCount, StreamWorkspace& ws,
                         const ListChunk<K>& chunk, vfloat<K>* dist) {
    PacketRay<K> p;
    PacketHit<K> h;
    gatherPacket(ws, chunk, p, h);
    const vbool<K> active = chunk.valid & (p.tnear <= h.t);
    if (ws.countCost) StreamLanes<K>(nullptr, ws, chunk.idx).visit(movemask(active));
    classifyOctant(p, movemask(active));
    for (int c = 0; c < liveCount; ++c) dist[c] = packetChildEntry<N, K>(node, live[c], p, h.t, active);
}

/// Splits the list of an inner node into one list per child (each as large as the list plus K of
/// slack for the vector loads of the next level) and pushes them, the one to visit first last, each
/// with its node or leaf blocks prefetched (`prefetchChild`, see the end). Returns how many.
/// The children are visited in the order of the nearest entry among their rays,
/// and where that ties, first the child that most rays enter before any other. The rays of a list
/// visit the children in the lists' order, not each in its own nearest-first order, and a ray that
/// visits a farther child before its nearest finds hits there that the nearest would have culled;
/// most rays of a path start on a surface inside some child (entry distance 0), so most children
/// tie on the nearest entry alone, and their order was the slots'. Against that (one thread, 512x512,
/// high build, the same process, two runs): bounce rays from inside Sponza visit 14.6 -> 13.1 nodes
/// and 4.9 -> 3.8 leaves per ray and trace 14-16% faster, the kitchen's 1-4%; diffuse rays -4% to +6%.
/// (The child most rays enter first, before the nearest entry: bounce rays as fast, diffuse rays
/// 1-9% slower.) The prefetch: most lists are popped after a nearer sibling's subtree, which gives it
/// time to land; without it the first load of a leaf block was a third of the single-ray finish's
/// samples (`perf annotate`, Sponza's bounce rays). Measured (`wideray_perf`, one thread, 512x512,
/// ABBA on one CPU, 6-10 rounds, `single` as the control): `stream` 1-9% faster on Sponza's diffuse
/// rays from inside and 3-13% on its bounce rays in three runs, 4-5% on the kitchen's.
template <int N, int K>
inline int splitByList(const SceneView<N>& scene, const StreamEntry& e, StreamWorkspace& ws, StreamEntry* push) {
    using F = vfloat<K>;
    const F inf(__builtin_huge_valf());
    const WideNode<N>& node = scene.nodes[e.ref.index()];
    const uint32_t top = e.restoreTop, region = e.end - e.begin + K;
    int live[N];
    const int liveCount = liveChildren(node, live);
    ws.reserveArena(top + liveCount * region + K);
    uint32_t childEnd[N];
    F closest[N];
    uint32_t firstOf[N];  // the rays that enter the child before any other
    for (int c = 0; c < liveCount; ++c) {
        childEnd[c] = top + c * region;
        closest[c] = inf;
        firstOf[c] = 0;
    }
    for (uint32_t at = e.begin; at < e.end; at += K) {
        const ListChunk<K> chunk = loadChunk<K>(&ws.arena[at], e.end - at);
        F dist[N];
        childEntries<N, K>(node, live, liveCount, ws, chunk, dist);
        F nearest = dist[0];
        vint<K> nearestChild(0);  // ties: the lower slot
        for (int c = 1; c < liveCount; ++c) {
            nearestChild = select(dist[c] < nearest, vint<K>(c), nearestChild);
            nearest = min(nearest, dist[c]);
        }
        for (int c = 0; c < liveCount; ++c) {
            const vbool<K> enters = dist[c] < inf;
            closest[c] = min(closest[c], dist[c]);
            firstOf[c] += uint32_t(__builtin_popcount(movemask(enters & (nearestChild == vint<K>(c)))));
            compressStore(&ws.arenaEntry[childEnd[c]], dist[c], enters);
            childEnd[c] += uint32_t(compressStore(&ws.arena[childEnd[c]], chunk.idx, enters));
        }
    }
    struct Order {
        uint32_t firstOf;
        float closest;
        int c;
        bool before(const Order& o) const {
            return closest != o.closest ? closest < o.closest : firstOf != o.firstOf ? firstOf > o.firstOf : c < o.c;
        }
    };
    Order order[N];
    int childCount = 0;
    for (int c = 0; c < liveCount; ++c) {
        if (childEnd[c] == top + c * region) continue;
        const Order o{firstOf[c], reduceMin(closest[c]), c};
        int j = childCount++;
        for (; j > 0 && o.before(order[j - 1]); --j) order[j] = order[j - 1];
        order[j] = o;
    }
    const uint32_t newTop = top + liveCount * region;
    for (int k = 0; k < childCount; ++k) {  // the last visited first, so that the first is popped first
        const int c = order[childCount - 1 - k].c;
        push[k] = {node.child[live[c]], top + c * region, childEnd[c], newTop, k < childCount - 1};
        prefetchChild(scene, push[k].ref);
    }
    return childCount;
}

/// How a ray of the list being split visits the node's children, in 32 bits: bit i says that it
/// enters child i, bits 8 + 3i .. 10 + 3i give child i's rank in the ray's nearest-first order.
inline int visitRank(uint32_t visits, int child) { return int(visits >> (8 + 3 * child)) & 7; }

/// Dynamic Ray Stream Traversal (Barringer and Akenine-Moller 2014) generalized to wide nodes: the
/// list is split into one list per (child, rank of that child in the ray's nearest-first order),
/// counted first so that the lists lie back to back, and pushed farthest rank first. Each ray thus
/// finishes the subtree of its nearest child before any list holds it for its next.
template <int N, int K>
inline int splitByRay(const SceneView<N>& scene, const StreamEntry& e, StreamWorkspace& ws, StreamEntry* push) {
    static_assert(N <= kMaxStreamNodeWidth, "the visit code and childEntries have room for eight children");
    using F = vfloat<K>;
    using I = vint<K>;
    const F inf(__builtin_huge_valf());
    const WideNode<N>& node = scene.nodes[e.ref.index()];
    const uint32_t count = e.end - e.begin;
    int live[N];
    const int liveCount = liveChildren(node, live);
    for (uint32_t at = e.begin; at < e.end; at += K) {
        const ListChunk<K> chunk = loadChunk<K>(&ws.arena[at], e.end - at);
        F dist[N];
        childEntries<N, K>(node, live, liveCount, ws, chunk, dist);
        for (int c = 0; c < liveCount; ++c) dist[c].store(&ws.childEntries[(at - e.begin) * N + live[c] * K]);
        I visits(0);
        for (int c = 0; c < liveCount; ++c) {
            const vbool<K> enters = dist[c] < inf;
            visits = visits + select(enters, I(1 << live[c]), I(0));
            const I rankStep(int32_t(1u << (8 + 3 * live[c])));
            for (int d = 0; d < liveCount; ++d) {
                if (d == c) continue;
                const vbool<K> nearer = d < c ? dist[d] <= dist[c] : dist[d] < dist[c];  // ties: lower slot first
                visits = visits + select(enters & nearer, rankStep, I(0));
            }
        }
        visits.store(&ws.visits[at - e.begin]);
    }
    uint32_t listSize[N * N] = {};  // [rank * N + slot]
    for (uint32_t j = 0; j < count; ++j) {
        const uint32_t v = uint32_t(ws.visits[j]);
        for (uint32_t m = v & 0xFF; m; m &= m - 1) {
            const int c = __builtin_ctz(m);
            ++listSize[visitRank(v, c) * N + c];
        }
    }
    uint32_t listBegin[N * N], cursor[N * N];
    uint32_t newTop = e.restoreTop;
    for (int l = 0; l < N * N; ++l) {
        listBegin[l] = cursor[l] = newTop;
        newTop += listSize[l];
    }
    ws.reserveArena(newTop + K);  // K of slack for the vector loads of the next level
    for (uint32_t j = 0; j < count; ++j) {
        const uint32_t v = uint32_t(ws.visits[j]);
        const int32_t ray = ws.arena[e.begin + j];
        const float* entries = &ws.childEntries[(j - j % K) * N + j % K];
        for (uint32_t m = v & 0xFF; m; m &= m - 1) {
            const int c = __builtin_ctz(m);
            const uint32_t to = cursor[visitRank(v, c) * N + c]++;
            ws.arena[to] = ray;
            ws.arenaEntry[to] = entries[c * K];
        }
    }
    int pushed = 0;
    for (int rank = N - 1; rank >= 0; --rank) {
        for (int c = N - 1; c >= 0; --c) {
            const int l = rank * N + c;
            if (listSize[l] == 0) continue;
            push[pushed++] = {node.child[c], listBegin[l], listBegin[l] + listSize[l], newTop, rank > 0};
            prefetchChild(scene, node.child[c]);
        }
    }
    return pushed;
}

/// Lists shorter than this fill too few lanes of a vector to gain on single rays: their rays finish
/// the subtree as single rays, with the single-ray kernel's SIMD box and triangle tests, taking turns
/// (traceInterleaved; 16 instead of 8 since then: within noise). A leaf's rays switch later, as their
/// single-ray test needs no set-up (measured on bounce rays, Sponza).
constexpr uint32_t kSingleRayListSize = 8, kSingleRayLeafListSize = 4;

/// The closest hit so far of a stream slot, as the single-ray kernel keeps it.
inline Hit slotHit(const StreamWorkspace& ws, int32_t s) {
    if (ws.prim[s] != kNoPrim) return {ws.tfar[s], ws.u[s], ws.v[s], uint32_t(ws.prim[s]), 0};
    if (ws.userGeomId[s] != kInvalidId) return {ws.tfar[s], ws.u[s], ws.v[s], ws.userPrimId[s], ws.userGeomId[s]};
    return {ws.tfar[s], 0, 0, kInvalidId, kInvalidId};
}

/// The triangle test's part of a stream slot's single-ray state.
inline WatertightRay<float, int32_t> slotWoop(const StreamWorkspace& ws, int32_t s) {
    return {ws.ox[s], ws.oy[s], ws.oz[s], ws.kx[s], ws.ky[s], ws.kz[s], ws.sx[s], ws.sy[s], ws.sz[s]};
}

/// The single-ray state of a stream slot: what makeSingleRayState computes for its ray (loadStream
/// computed the same constants, lane by lane), without its six divisions.
inline SingleRayState slotState(const StreamWorkspace& ws, int32_t s) {
    return {makeBoxRay(makeSlabRay(ws.ox[s], ws.oy[s], ws.oz[s], ws.rdx[s], ws.rdy[s], ws.rdz[s])), slotWoop(ws, s)};
}

/// Writes a stream slot's answer from a single-ray traversal of part of the tree: its hit where it is
/// nearer than the slot's (another part's traversal may have found a nearer one meanwhile).
inline void storeSlotResult(StreamWorkspace& ws, int32_t s, const Hit& hit, bool occluded, const TraversalCost& cost) {
    if (ws.countCost) {
        ws.costNodes[s] += cost.nodes;
        ws.costLeaves[s] += cost.leaves;
        ws.costPrimitives[s] += cost.primitives;
    }
    if (occluded) {
        ws.tfar[s] = -__builtin_huge_valf();
    } else if (hit.valid() && isCloser(hit.t, hit.geomId, hit.primId, slotHit(ws, s))) {
        ws.tfar[s] = hit.t;
        ws.u[s] = hit.u;
        ws.v[s] = hit.v;
        if (hit.geomId == 0) {
            ws.prim[s] = int32_t(hit.primId);
        } else {
            ws.prim[s] = kNoPrim;
            ws.userGeomId[s] = hit.geomId;
            ws.userPrimId[s] = hit.primId;
        }
    }
}

/// The rays of a short list at a leaf, one by one.
template <bool AnyHit, class Leaves>
inline void traceLeafSingly(const Leaves& leaves, const Ray* rays, const StreamEntry& e, StreamWorkspace& ws) {
    for (uint32_t at = e.begin; at < e.end; ++at) {
        const int32_t s = ws.arena[at];
        if (!(ws.tnear[s] <= ws.tfar[s])) continue;  // occluded already
        Hit hit = slotHit(ws, s);
        TraversalCost cost;
        const BlockRay<kBlockSize> blockRay(slotWoop(ws, s));
        const bool occluded = leaves.template single<kBlockSize, AnyHit>(e.ref, blockRay, rays[ws.rayOf[s]], hit, cost);
        storeSlotResult(ws, s, hit, occluded, cost);
    }
}

/// The rays of short lists at inner nodes, gathered to trace their subtrees taking turns
/// (traceInterleaved) once there are kCapacity or a longer list at an inner node is popped (which
/// culls by their hits). A ray may be held more than once, from lists of several children of a node:
/// each finds the closest hit in its own subtree and the nearest is kept (storeSlotResult), as are
/// hits that a leaf's list finds meanwhile. Against tracing each list's rays on their own (3.1 rays
/// per list): batches of 5.2 rays on Sponza's bounce rays from inside (1.7% more ray traversals),
/// `stream` 3% faster there and 3-5% on the kitchen's diffuse and bounce rays (4-5 ABBA rounds,
/// `single` as the control). Up to 16 rays (8.5 per batch, 4.5% more traversals): no faster. Each
/// ray held once (a list that holds a held ray waiting for the batch): 4.6 rays per batch, no faster.
template <int N>
struct InterleavedBatch {
    static constexpr int kCapacity = 8;
    static_assert(kCapacity >= int(kSingleRayListSize) - 1, "a short list fits an empty batch");
    InterleavedRay<N> traced[kCapacity];
    int32_t slot[kCapacity];
    int count = 0;

    bool hasRoomFor(const StreamEntry& e) const { return count + int(e.end - e.begin) <= kCapacity; }

    void add(const Ray* rays, const StreamEntry& e, const StreamWorkspace& ws) {
        for (uint32_t at = e.begin; at < e.end; ++at) {
            const int32_t s = ws.arena[at];
            if (!(ws.tnear[s] <= ws.tfar[s])) continue;  // occluded already
            InterleavedRay<N>& r = traced[count];
            r.ray = &rays[ws.rayOf[s]];
            r.state = slotState(ws, s);
            r.hit = slotHit(ws, s);
            r.cost = TraversalCost{};
            r.next = e.ref;
            slot[count++] = s;
        }
    }

    template <bool AnyHit, class Leaves>
    void trace(const SceneView<N>& scene, const Leaves& leaves, StreamWorkspace& ws) {
        traceInterleaved<N, AnyHit>(scene, leaves, traced, count);
        for (int k = 0; k < count; ++k) storeSlotResult(ws, slot[k], traced[k].hit, traced[k].occluded, traced[k].cost);
        count = 0;
    }
};

/// Keeps, in order, the rays of a list that still enter its node: those whose hit so far (found
/// under a nearer sibling) is not nearer than their entry (the box test's own culling, as a
/// single-ray traversal does when it pops the node; occluded rays have tfar = -inf). Returns the
/// list's new end. Without it such rays went on to the node's children, or to its leaf, each tested
/// and culled there.
template <int K>
inline uint32_t dropCulledRays(const StreamEntry& e, StreamWorkspace& ws) {
    using F = vfloat<K>;
    uint32_t kept = e.begin, at = e.begin;
    // Whole chunks: the compressed stores write K entries from `kept`, which is no further than `at`,
    // so they overwrite only what has been read.
    for (; at + K <= e.end; at += K) {
        const ListChunk<K> chunk = loadChunk<K>(&ws.arena[at], K);
        const F entry = F::loadu(&ws.arenaEntry[at]);
        const vbool<K> keep = entry <= chunk.fetch(ws.tfar) * F(kRobustFarScale);
        compressStore(&ws.arenaEntry[kept], entry, keep);
        kept += uint32_t(compressStore(&ws.arena[kept], chunk.idx, keep));
    }
    // The rest one by one: a whole vector stored there could reach past the list into the next one.
    for (; at < e.end; ++at) {
        const int32_t ray = ws.arena[at];
        const float entry = ws.arenaEntry[at];
        ws.arena[kept] = ray;
        ws.arenaEntry[kept] = entry;
        kept += entry <= ws.tfar[ray] * kRobustFarScale ? 1 : 0;
    }
    return kept;
}

template <int N, int K, bool AnyHit, StreamOrder Order, class Leaves>
inline void traceStreamLists(const SceneView<N>& scene, const Ray* rays, size_t n, StreamWorkspace& ws) {
    const Leaves leaves{scene.leaves};
    auto* stack = static_cast<StreamEntry*>(ws.reserveStack(sizeof(StreamEntry) * kStreamStackSize<N>));
    int sp = 0;
    ws.reserveArena(n + K);
    for (size_t i = 0; i < n; ++i) ws.arena[i] = int32_t(i);
    stack[sp++] = {scene.root, 0, uint32_t(n), uint32_t(n), false};
    InterleavedBatch<N> batch;
    auto isShort = [](const StreamEntry& e) {
        return e.end - e.begin < (e.ref.isLeaf() ? kSingleRayLeafListSize : kSingleRayListSize);
    };
    while (sp > 0) {
        StreamEntry e = stack[--sp];
        if (batch.count > 0 && (!(isShort(e) || e.ref.isLeaf()) || !batch.hasRoomFor(e)))
            batch.template trace<AnyHit>(scene, leaves, ws);
        if (e.afterSibling) e.end = dropCulledRays<K>(e, ws);
        if (e.end == e.begin) continue;
        if (isShort(e)) {
            if (e.ref.isLeaf()) traceLeafSingly<AnyHit>(leaves, rays, e, ws);
            else batch.add(rays, e, ws);
        } else if (e.ref.isLeaf()) traceStreamLeaf<K, AnyHit>(leaves, rays, e, ws);
        else if constexpr (Order == StreamOrder::ByList) sp += splitByList<N, K>(scene, e, ws, stack + sp);
        else sp += splitByRay<N, K>(scene, e, ws, stack + sp);
    }
    if (batch.count > 0) batch.template trace<AnyHit>(scene, leaves, ws);
}

/// Closest hits (AnyHit = false) or occlusion of `count` rays as one stream, and their costs where
/// `costsOut` is given.
template <int N, int K, bool AnyHit, StreamOrder Order, class Leaves = SceneLeafIntersector<N>>
inline void traceStream(const SceneView<N>& scene, const Ray* rays, size_t count, Hit* hitsOut, uint8_t* occludedOut,
                        StreamWorkspace& ws, TraversalCost* costsOut = nullptr) {
    for (size_t i = 0; i < count; ++i) {
        if constexpr (AnyHit) occludedOut[i] = 0;
        else hitsOut[i] = Hit{};
    }
    size_t n = loadStream<K>(rays, count, ws);
    ws.countCost = costsOut != nullptr;
    if (costsOut) {
        for (size_t i = 0; i < count; ++i) costsOut[i] = TraversalCost{};
        for (size_t s = 0; s < n; ++s) ws.costNodes[s] = ws.costLeaves[s] = ws.costPrimitives[s] = 0;
    }
    if (n == 0) return;
    traceStreamLists<N, K, AnyHit, Order, Leaves>(scene, rays, n, ws);
    for (size_t s = 0; s < n; ++s) {
        const uint32_t i = ws.rayOf[s];
        if constexpr (AnyHit) {
            occludedOut[i] = ws.tfar[s] == -__builtin_huge_valf() ? 1 : 0;
        } else {
            const Hit hit = ws.prim[s] != kNoPrim        ? Hit{ws.tfar[s], ws.u[s], ws.v[s], uint32_t(ws.prim[s]), 0}
                            : ws.userGeomId[s] != kInvalidId ? Hit{ws.tfar[s], ws.u[s], ws.v[s], ws.userPrimId[s], ws.userGeomId[s]}
                                                             : Hit{};
            hitsOut[i] = hit;
        }
        if (costsOut) costsOut[i] = {ws.costNodes[s], ws.costLeaves[s], ws.costPrimitives[s]};
    }
}

} // namespace WIDERAY_ISA
} // namespace wideray
