// The watertight ray/triangle test (kernels/watertight.h) with K = 1 ray and a packet of K = 4 rays
// against one triangle, the per-ray shear precomputed as the kernels do. This file is compiled with
// the baseline flags, so K = 4 is the SSE4.2 variant.
#include <benchmark/benchmark.h>

#include <limits>
#include <vector>

#include "core/ray.h"
#include "kernels/watertight.h"
#include "perf_inputs.h"

namespace wideray::perf {
namespace {

constexpr size_t kCount = 1024;  // triangles and rays; a power of two

struct Triangles {
    std::vector<float> v0x, v0y, v0z, v1x, v1y, v1z, v2x, v2y, v2z;
};

/// Triangles of edge about 1 around the origin; rays from a sphere of radius 4 toward points near
/// the origin, so that about a tenth of the tests hit.
Triangles randomTriangles(RandomFloats& random) {
    Triangles t;
    for (size_t i = 0; i < kCount; ++i) {
        glm::vec3 c(random(-0.5f, 0.5f), random(-0.5f, 0.5f), random(-0.5f, 0.5f));
        auto vertex = [&] { return c + glm::vec3(random(-0.7f, 0.7f), random(-0.7f, 0.7f), random(-0.7f, 0.7f)); };
        glm::vec3 a = vertex(), b = vertex(), d = vertex();
        t.v0x.push_back(a.x), t.v0y.push_back(a.y), t.v0z.push_back(a.z);
        t.v1x.push_back(b.x), t.v1y.push_back(b.y), t.v1z.push_back(b.z);
        t.v2x.push_back(d.x), t.v2y.push_back(d.y), t.v2z.push_back(d.z);
    }
    return t;
}

std::vector<Ray> randomRays(RandomFloats& random) { return raysIntoCube(random, kCount, 0.3f); }

/// Rays i*K .. i*K+K-1 as one K-wide watertight ray (K = 1: plain floats).
template <int K>
std::vector<WatertightRay<simd::vfloat<K>, simd::vint<K>>> packetsOf(const std::vector<Ray>& rays) {
    using F = simd::vfloat<K>;
    std::vector<WatertightRay<F, simd::vint<K>>> packets;
    for (size_t i = 0; i < rays.size(); i += K) {
        if constexpr (K == 1) {
            const Ray& r = rays[i];
            packets.push_back(makeWatertightRay<float, int32_t>(r.ox, r.oy, r.oz, r.dx, r.dy, r.dz));
        } else {
            alignas(64) float o[3][K], d[3][K];
            for (int k = 0; k < K; ++k) {
                const Ray& r = rays[i + k];
                o[0][k] = r.ox, o[1][k] = r.oy, o[2][k] = r.oz;
                d[0][k] = r.dx, d[1][k] = r.dy, d[2][k] = r.dz;
            }
            packets.push_back(makeWatertightRay<F, simd::vint<K>>(F::load(o[0]), F::load(o[1]), F::load(o[2]),
                                                                 F::load(d[0]), F::load(d[1]), F::load(d[2])));
        }
    }
    return packets;
}

template <int K>
void triangleTest(benchmark::State& state) {
    using F = simd::vfloat<K>;
    using B = simd::vbool<K>;
    RandomFloats random;
    Triangles tri = randomTriangles(random);
    auto packets = packetsOf<K>(randomRays(random));
    constexpr size_t kPackets = kCount / K;
    size_t i = 0, hits = 0;
    for (auto _ : state) {
        // Each pass over the triangles shifts the packets by one, so that every pair comes up.
        const auto& ray = packets[(i + i / kCount) % kPackets];
        size_t j = i % kCount;
        F t(std::numeric_limits<float>::infinity()), u(0.0f), v(0.0f);
        B hit = intersectWatertight(ray, B(true), F(tri.v0x[j]), F(tri.v0y[j]), F(tri.v0z[j]), F(tri.v1x[j]),
                                    F(tri.v1y[j]), F(tri.v1z[j]), F(tri.v2x[j]), F(tri.v2y[j]), F(tri.v2z[j]),
                                    F(0.0f), F(std::numeric_limits<float>::infinity()), t, u, v);
        hits += __builtin_popcount(simd::movemask(hit));
        benchmark::DoNotOptimize(t);
        ++i;
    }
    double tests = double(state.iterations()) * K;
    state.counters["rays/s"] = benchmark::Counter(tests, benchmark::Counter::kIsRate);
    state.counters["hit_fraction"] = tests > 0 ? double(hits) / tests : 0.0;
}

BENCHMARK(triangleTest<1>)->Name("triangleTest/K1/scalar");
BENCHMARK(triangleTest<4>)->Name("triangleTest/K4/simd4_sse42_baseline");

} // namespace
} // namespace wideray::perf
