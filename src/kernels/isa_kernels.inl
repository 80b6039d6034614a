// The kernels of one ISA, compiled from the same source for each: a translation unit in
// kernels/isa/ defines WIDERAY_ISA (the namespace) and WIDERAY_ISA_TABLE (the table's name) and
// includes this file with its ISA's compiler flags.
#include "kernels/isa_kernels.h"
#include "kernels/traverse_large_packet.h"
#include "kernels/traverse_stream.h"

namespace wideray {
inline namespace WIDERAY_ISA {
namespace {

template <int N>
void singleIntersect(const SceneView<N>& scene, const Ray* rays, Hit* hits, size_t count, TraversalCost* costs) {
    for (size_t i = 0; i < count; ++i) {
        TraversalCost cost;
        Hit hit;
        hit.t = rays[i].tfar;
        traceSingle<N, kNodeSimdWidth<N>, kBlockSize, false>(scene, rays[i], hit, cost);
        hits[i] = hit.valid() ? hit : Hit{};
        if (costs) costs[i] = cost;
    }
}

template <int N>
void singleOccluded(const SceneView<N>& scene, const Ray* rays, uint8_t* occluded, size_t count) {
    for (size_t i = 0; i < count; ++i) {
        TraversalCost cost;
        Hit hit;
        hit.t = rays[i].tfar;
        occluded[i] = traceSingle<N, kNodeSimdWidth<N>, kBlockSize, true>(scene, rays[i], hit, cost) ? 1 : 0;
    }
}

/// Any-hit with the shadow cache: the cached block first, then a traversal that remembers the
/// block that blocked the ray. The answers are the same as without the cache.
template <int N>
void singleOccludedCached(const SceneView<N>& scene, const Ray* rays, uint8_t* occluded, size_t count,
                          ShadowCache& cache) {
    const TriangleBvhView<N>& tri = scene.triangles;
    for (size_t i = 0; i < count; ++i) {
        const Ray& ray = rays[i];
        occluded[i] = 0;
        if (!isValidRay(ray)) continue;
        const SingleRayState s = makeSingleRayState(ray);
        Hit hit;
        hit.t = ray.tfar;
        ++cache.queries;
        if (cache.block != kInvalidId && intersectBlock<kBlockSize, true>(tri.blocks[cache.block], s, ray, hit)) {
            ++cache.hits;
            occluded[i] = 1;
            continue;
        }
        bool blocked = false;
        TraversalCost cost;
        if (tri.blocks)
            traverseWide<N, kNodeSimdWidth<N>>(
                tri.nodes, tri.root, s.box, ray.tnear, [&] { return hit.t; },
                [&](uint32_t first, uint32_t n) {
                    for (uint32_t b = first; b < first + n; ++b)
                        if (intersectBlock<kBlockSize, true>(tri.blocks[b], s, ray, hit)) {
                            cache.block = b;
                            return blocked = true;
                        }
                    return false;
                },
                cost);
        if (!blocked && scene.user.prims)
            blocked = traceUser<N, kNodeSimdWidth<N>, true>(scene.user, ray, s, hit, cost);
        occluded[i] = blocked ? 1 : 0;
    }
}

/// Packets of K consecutive rays; per-ray costs (the cost AOV) come from the single-ray kernel.
template <int N, int K>
void packetIntersect(const SceneView<N>& scene, const Ray* rays, Hit* hits, size_t count, TraversalCost* costs) {
    if (costs) return singleIntersect<N>(scene, rays, hits, count, costs);
    for (size_t i = 0; i < count; i += K)
        tracePacket<N, K, false>(scene, rays + i, int(count - i < K ? count - i : K), hits + i, nullptr);
}

template <int N, int K>
void packetOccluded(const SceneView<N>& scene, const Ray* rays, uint8_t* occluded, size_t count) {
    for (size_t i = 0; i < count; i += K)
        tracePacket<N, K, true>(scene, rays + i, int(count - i < K ? count - i : K), nullptr, occluded + i);
}

/// Packets of 256 rays (a 16x16 tile in Morton order), sub-packets as wide as the ISA allows.
template <int N>
void largePacketIntersect(const SceneView<N>& scene, const Ray* rays, Hit* hits, size_t count, TraversalCost* costs) {
    if (costs) return singleIntersect<N>(scene, rays, hits, count, costs);
    constexpr int K = kMaxWidth, P = 256 / K;
    for (size_t i = 0; i < count; i += K * P)
        traceLargePacket<N, K, P, false>(scene, rays + i, int(count - i < K * P ? count - i : K * P), hits + i, nullptr);
}

template <int N>
void largePacketOccluded(const SceneView<N>& scene, const Ray* rays, uint8_t* occluded, size_t count) {
    constexpr int K = kMaxWidth, P = 256 / K;
    for (size_t i = 0; i < count; i += K * P)
        traceLargePacket<N, K, P, true>(scene, rays + i, int(count - i < K * P ? count - i : K * P), nullptr,
                                        occluded + i);
}

/// Streams of up to kStreamSize rays, SIMD across the widest vector of the ISA.
constexpr size_t kStreamSize = 4096;

template <int N, StreamOrder Order>
void streamIntersect(const SceneView<N>& scene, const Ray* rays, Hit* hits, size_t count, TraversalCost* costs) {
    if (costs) return singleIntersect<N>(scene, rays, hits, count, costs);
    StreamWorkspace& ws = StreamWorkspace::forThisThread();
    for (size_t i = 0; i < count; i += kStreamSize)
        traceStream<N, kMaxWidth, false, Order>(scene, rays + i, count - i < kStreamSize ? count - i : kStreamSize,
                                                hits + i, nullptr, ws);
}

template <int N, StreamOrder Order>
void streamOccluded(const SceneView<N>& scene, const Ray* rays, uint8_t* occluded, size_t count) {
    StreamWorkspace& ws = StreamWorkspace::forThisThread();
    for (size_t i = 0; i < count; i += kStreamSize)
        traceStream<N, kMaxWidth, true, Order>(scene, rays + i, count - i < kStreamSize ? count - i : kStreamSize,
                                               nullptr, occluded + i, ws);
}

template <int N>
IsaKernelTable<N> makeTable() {
    IsaKernelTable<N> t;
    t.single = {"single", &singleIntersect<N>, &singleOccluded<N>, &singleOccludedCached<N>};
    t.packet4 = {"packet4", &packetIntersect<N, 4>, &packetOccluded<N, 4>};
#if defined(__AVX2__)
    t.packet8 = {"packet8", &packetIntersect<N, 8>, &packetOccluded<N, 8>};
#endif
#if defined(__AVX512F__)
    t.packet16 = {"packet16", &packetIntersect<N, 16>, &packetOccluded<N, 16>};
#endif
    t.packet256 = {"packet256", &largePacketIntersect<N>, &largePacketOccluded<N>};
    t.stream = {"stream", &streamIntersect<N, StreamOrder::ByList>, &streamOccluded<N, StreamOrder::ByList>};
    t.drst = {"drst", &streamIntersect<N, StreamOrder::ByRay>, &streamOccluded<N, StreamOrder::ByRay>};
    return t;
}

} // namespace
} // namespace WIDERAY_ISA

template <> IsaKernelTable<4> WIDERAY_ISA_TABLE<4>() { return makeTable<4>(); }
template <> IsaKernelTable<8> WIDERAY_ISA_TABLE<8>() { return makeTable<8>(); }

} // namespace wideray
