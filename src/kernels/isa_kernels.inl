// The kernels of one ISA, compiled from the same source for each: a translation unit in
// kernels/isa/ defines WIDERAY_ISA (the namespace) and WIDERAY_ISA_TABLE (the table's name) and
// includes this file with its ISA's compiler flags.
#include "kernels/kernel_registry.h"
#include "kernels/traverse_large_packet.h"
#include "kernels/traverse_stream.h"

namespace wideray {
inline namespace WIDERAY_ISA {
namespace {

/// One ray at a time: NodeW children and TriW triangles per box and triangle test. NodeW = TriW = 1
/// is the reference (plain scalar loops, each ray's constants made on their own); the SIMD kernels
/// make their rays' constants kMaxWidth at a time (forEachRayState). With Counting, each ray's work
/// goes to costs[i].
template <int N, int NodeW, int TriW, bool AnyHit, bool Counting, class Visit>
void forEachSingleRayCounted(const SceneView<N>& scene, const Ray* rays, size_t count, TraversalCost* costs,
                             const Visit& visit) {
    using Leaves = SceneLeafIntersector<N>;
    auto trace = [&](size_t i, const SingleRayState* s) {
        TraversalCost cost;
        Hit hit;
        hit.t = rays[i].tfar;
        bool occluded = false;
        if constexpr (NodeW == 1) occluded = traceSingle<N, NodeW, TriW, AnyHit, Leaves, Counting>(scene, rays[i], hit, cost);
        else if (s)
            occluded = traceSubtree<N, NodeW, TriW, AnyHit, Leaves, Counting>(
                scene, scene.root, rays[i], s->box, [&] { return s->woop; }, hit, cost);
        visit(i, hit, occluded);
        if constexpr (Counting) costs[i] = cost;
    };
    if constexpr (NodeW == 1)
        for (size_t i = 0; i < count; ++i) trace(i, nullptr);
    else
        forEachRayState<kMaxWidth>(rays, count, trace);
}

template <int N, int NodeW, int TriW, bool AnyHit, class Visit>
void forEachSingleRay(const SceneView<N>& scene, const Ray* rays, size_t count, TraversalCost* costs, const Visit& visit) {
    if (costs) forEachSingleRayCounted<N, NodeW, TriW, AnyHit, true>(scene, rays, count, costs, visit);
    else forEachSingleRayCounted<N, NodeW, TriW, AnyHit, false>(scene, rays, count, costs, visit);
}

template <int N, int NodeW, int TriW>
void singleIntersect(const SceneView<N>& scene, const Ray* rays, Hit* hits, size_t count, TraversalCost* costs) {
    forEachSingleRay<N, NodeW, TriW, false>(scene, rays, count, costs, [&](size_t i, const Hit& hit, bool) {
        hits[i] = hit.valid() ? hit : Hit{};
    });
}

template <int N, int NodeW, int TriW>
void singleOccluded(const SceneView<N>& scene, const Ray* rays, uint8_t* occluded, size_t count, TraversalCost* costs) {
    forEachSingleRay<N, NodeW, TriW, true>(scene, rays, count, costs, [&](size_t i, const Hit&, bool o) {
        occluded[i] = o ? 1 : 0;
    });
}

/// Any-hit with the shadow cache: the cached blocks first (the latest occluder first), then a
/// traversal that caches the block that blocks the ray. The answers are the same as without the cache.
template <int N>
void singleOccludedCached(const SceneView<N>& scene, const Ray* rays, uint8_t* occluded, size_t count,
                          ShadowCache& cache) {
    forEachRayState<kMaxWidth>(rays, count, [&](size_t i, const SingleRayState* state) {
        const Ray& ray = rays[i];
        occluded[i] = 0;
        if (!state) return;
        const SingleRayState& s = *state;
        const BlockRay<kBlockSize> blockRay(s.woop);
        Hit hit;
        hit.t = ray.tfar;
        ++cache.queries;
        int entry = 0;
        while (entry < ShadowCache::kBlocks && cache.blocks[entry] != ShadowCache::kEmpty &&
               !intersectBlock<kBlockSize, true>(scene.leaves.blocks[cache.blocks[entry]], blockRay, ray, hit))
            ++entry;
        if (entry < ShadowCache::kBlocks && cache.blocks[entry] != ShadowCache::kEmpty) {
            ++cache.hits;
            cache.promote(entry);
            occluded[i] = 1;
            return;
        }
        TraversalCost cost;  // not reported
        occluded[i] = traceSubtree<N, kNodeSimdWidth<N>, kBlockSize, true, SceneLeafIntersector<N>, false>(
            scene, scene.root, ray, s.box, [&] { return s.woop; }, hit, cost, &cache.found);
        cache.remember();
    });
}

/// Packets of K consecutive rays.
template <int N, int K>
void packetIntersect(const SceneView<N>& scene, const Ray* rays, Hit* hits, size_t count, TraversalCost* costs) {
    IncoherentPackets history(scene);
    for (size_t i = 0; i < count; i += K)
        tracePacket<N, K, false>(scene, rays + i, int(count - i < K ? count - i : K), hits + i, nullptr,
                                 costs ? costs + i : nullptr, &history);
}

template <int N, int K>
void packetOccluded(const SceneView<N>& scene, const Ray* rays, uint8_t* occluded, size_t count, TraversalCost* costs) {
    for (size_t i = 0; i < count; i += K)
        tracePacket<N, K, true>(scene, rays + i, int(count - i < K ? count - i : K), nullptr, occluded + i,
                                costs ? costs + i : nullptr);
}

template <int N, int K>
void packetOccludedCached(const SceneView<N>& scene, const Ray* rays, uint8_t* occluded, size_t count,
                          ShadowCache& cache) {
    for (size_t i = 0; i < count; i += K)
        tracePacket<N, K, true>(scene, rays + i, int(count - i < K ? count - i : K), nullptr, occluded + i, nullptr,
                                nullptr, &cache);
}

/// Packets of 256 rays (a 16x16 tile in Morton order), sub-packets as wide as the ISA allows.
template <int N>
void largePacketIntersect(const SceneView<N>& scene, const Ray* rays, Hit* hits, size_t count, TraversalCost* costs) {
    constexpr int K = kMaxWidth, P = 256 / K;
    IncoherentPackets history(scene);
    for (size_t i = 0; i < count; i += K * P)
        traceLargePacket<N, K, P, false>(scene, rays + i, int(count - i < K * P ? count - i : K * P), hits + i, nullptr,
                                         costs ? costs + i : nullptr, &history);
}

template <int N>
void largePacketOccluded(const SceneView<N>& scene, const Ray* rays, uint8_t* occluded, size_t count,
                         TraversalCost* costs) {
    constexpr int K = kMaxWidth, P = 256 / K;
    for (size_t i = 0; i < count; i += K * P)
        traceLargePacket<N, K, P, true>(scene, rays + i, int(count - i < K * P ? count - i : K * P), nullptr,
                                        occluded + i, costs ? costs + i : nullptr);
}

template <int N>
void largePacketOccludedCached(const SceneView<N>& scene, const Ray* rays, uint8_t* occluded, size_t count,
                               ShadowCache& cache) {
    constexpr int K = kMaxWidth, P = 256 / K;
    for (size_t i = 0; i < count; i += K * P)
        traceLargePacket<N, K, P, true>(scene, rays + i, int(count - i < K * P ? count - i : K * P), nullptr,
                                        occluded + i, nullptr, nullptr, &cache);
}

/// Streams of up to kStreamSize rays, SIMD across the widest vector of the ISA. The largest the issue
/// allows (1K-4K) measured fastest: 2048-ray streams 3% and 8% slower on Sponza's diffuse and bounce
/// rays from inside, 5% and 15% on the kitchen's; 1024-ray streams 10% and 16% slower on Sponza's
/// (ABBA on one CPU, 3-4 rounds, `single` as the control; high build, 512x512).
constexpr size_t kStreamSize = 4096;

template <int N, StreamOrder Order>
void streamIntersect(const SceneView<N>& scene, const Ray* rays, Hit* hits, size_t count, TraversalCost* costs) {
    StreamWorkspace& ws = StreamWorkspace::forThisThread();
    for (size_t i = 0; i < count; i += kStreamSize)
        traceStream<N, kMaxWidth, false, Order>(scene, rays + i, count - i < kStreamSize ? count - i : kStreamSize,
                                                hits + i, nullptr, ws, costs ? costs + i : nullptr);
}

template <int N, StreamOrder Order>
void streamOccluded(const SceneView<N>& scene, const Ray* rays, uint8_t* occluded, size_t count, TraversalCost* costs) {
    StreamWorkspace& ws = StreamWorkspace::forThisThread();
    for (size_t i = 0; i < count; i += kStreamSize)
        traceStream<N, kMaxWidth, true, Order>(scene, rays + i, count - i < kStreamSize ? count - i : kStreamSize,
                                               nullptr, occluded + i, ws, costs ? costs + i : nullptr);
}

/// A K-wide packet kernel where this ISA's vectors are that wide, null entry points elsewhere.
template <int N, int K>
Kernel<N> packetKernel(const char* name, const char* description, const char* counterpart, Isa minimumIsa) {
    Kernel<N> k{name, description, counterpart, minimumIsa};
    if constexpr (K <= kMaxWidth) {
        k.intersect = &packetIntersect<N, K>;
        k.occluded = &packetOccluded<N, K>;
        k.occludedCached = &packetOccludedCached<N, K>;
    }
    return k;
}

/// A stream kernel; DRST only on nodes of up to kMaxStreamNodeWidth children (its visit code holds
/// each ray's rank of every child in 32 bits), null entry points on wider ones.
template <int N, StreamOrder Order>
Kernel<N> streamKernel(const char* name, const char* description) {
    Kernel<N> k{name, description, "rtcIntersect1M", Isa::Sse42};
    if constexpr (Order == StreamOrder::ByList || N <= kMaxStreamNodeWidth) {
        k.intersect = &streamIntersect<N, Order>;
        k.occluded = &streamOccluded<N, Order>;
    }
    return k;
}

template <int N>
KernelTable<N> makeTable() {
    return {{{
        {"scalar", "the reference: one ray, plain loops over the children and the triangles",
         "rtcIntersect1", Isa::Sse42, &singleIntersect<N, 1, 1>, &singleOccluded<N, 1, 1>},
        {"single", "one ray, SIMD box test of all children, SIMD test of a leaf's 4-triangle blocks", "rtcIntersect1",
         Isa::Sse42, &singleIntersect<N, kNodeSimdWidth<N>, kBlockSize>,
         &singleOccluded<N, kNodeSimdWidth<N>, kBlockSize>, &singleOccludedCached<N>},
        packetKernel<N, 4>("packet4", "4 rays (2x2 pixels) walk the tree together", "rtcIntersect4", Isa::Sse42),
        packetKernel<N, 8>("packet8", "8 rays (4x2 pixels) walk the tree together", "rtcIntersect8", Isa::Avx2),
        packetKernel<N, 16>("packet16", "16 rays (4x4 pixels) walk the tree together", "rtcIntersect16", Isa::Avx512),
        {"packet256", "256 rays (16x16 pixels): inner nodes tested once by interval arithmetic, leaves per sub-packet",
         "rtcIntersect16", Isa::Sse42, &largePacketIntersect<N>, &largePacketOccluded<N>, &largePacketOccludedCached<N>},
        streamKernel<N, StreamOrder::ByList>(
            "stream", "sorted streams of up to 4096 rays, filtered node by node into one list per child"),
        streamKernel<N, StreamOrder::ByRay>(
            "drst", "sorted streams in which each ray visits its children in its own order (Dynamic Ray Stream Traversal)"),
    }}};
}

} // namespace
} // namespace WIDERAY_ISA

template <> KernelTable<4> WIDERAY_ISA_TABLE<4>() { return makeTable<4>(); }
template <> KernelTable<8> WIDERAY_ISA_TABLE<8>() { return makeTable<8>(); }
template <> KernelTable<16> WIDERAY_ISA_TABLE<16>() { return makeTable<16>(); }

} // namespace wideray
