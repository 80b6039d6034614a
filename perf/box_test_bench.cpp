// One ray against the N child boxes of a wide node (kernels/box_test.h): the scalar loop (W = 1) and
// 4-wide SIMD. This file is compiled with the baseline flags, so the SIMD variant is the SSE4.2 one.
#include <benchmark/benchmark.h>

#include <vector>

#include "kernels/box_test.h"
#include "perf_inputs.h"

namespace wideray::perf {
namespace {

constexpr size_t kCount = 1024;  // nodes and rays; a power of two, and small enough to stay in L2

template <int N>
std::vector<WideNode<N>> randomNodes(RandomFloats& random) {
    std::vector<WideNode<N>> nodes(kCount);
    for (WideNode<N>& node : nodes)
        for (int i = 0; i < N; ++i) {
            glm::vec3 c(random(-1, 1), random(-1, 1), random(-1, 1));
            glm::vec3 h(random(0.05f, 0.4f), random(0.05f, 0.4f), random(0.05f, 0.4f));
            node.lowerX[i] = c.x - h.x, node.upperX[i] = c.x + h.x;
            node.lowerY[i] = c.y - h.y, node.upperY[i] = c.y + h.y;
            node.lowerZ[i] = c.z - h.z, node.upperZ[i] = c.z + h.z;
            node.child[i] = NodeRef::inner(0);
        }
    return nodes;
}

/// Rays from a sphere of radius 4 toward points inside the node boxes' range: about half the
/// children are hit.
std::vector<BoxRay> randomBoxRays(RandomFloats& random) {
    std::vector<BoxRay> rays;
    for (const Ray& r : raysIntoCube(random, kCount, 0.5f)) rays.push_back(makeBoxRay(r.ox, r.oy, r.oz, r.dx, r.dy, r.dz));
    return rays;
}

template <int N, int W>
void boxTest(benchmark::State& state) {
    RandomFloats random;
    std::vector<WideNode<N>> nodes = randomNodes<N>(random);
    std::vector<ChildBoxTest<N, W>> tests;
    for (const BoxRay& ray : randomBoxRays(random)) tests.emplace_back(ray);
    alignas(64) float tEntry[N];
    size_t i = 0;
    for (auto _ : state) {
        // Each pass over the nodes shifts the rays by one, so that every pair comes up.
        const ChildBoxTest<N, W>& intersectChildren = tests[(i + i / kCount) % kCount];
        uint32_t mask = intersectChildren(nodes[i % kCount], 0.0f, 1e30f, tEntry);
        benchmark::DoNotOptimize(mask);
        benchmark::DoNotOptimize(tEntry);
        ++i;
    }
    state.counters["rays/s"] = benchmark::Counter(double(state.iterations()), benchmark::Counter::kIsRate);
    state.counters["boxes/s"] = benchmark::Counter(double(state.iterations()) * N, benchmark::Counter::kIsRate);
}

BENCHMARK(boxTest<4, 1>)->Name("boxTest/N4/scalar");
BENCHMARK(boxTest<4, 4>)->Name("boxTest/N4/simd4_sse42_baseline");
BENCHMARK(boxTest<8, 1>)->Name("boxTest/N8/scalar");
BENCHMARK(boxTest<8, 4>)->Name("boxTest/N8/simd4_sse42_baseline");

} // namespace
} // namespace wideray::perf
