// The whole build of our acceleration structure (binned SAH binary BVH, collapse to 8 wide, leaf
// blocks; accel/scene_accel.h) by mesh size: generated icospheres and tori, then the shared meshes
// that are present, each built fast and at high quality (spatial splits; names ending in /high). The
// build runs on all hardware threads through oneTBB, with flush-to-zero and denormals-are-zero as in
// wideray's commands and library.
#include <benchmark/benchmark.h>

#include <memory>
#include <string>
#include <vector>

#include "core/fp_mode.h"
#include "io/mesh_generators.h"
#include "accel/scene_accel.h"
#include "perf_inputs.h"

namespace wideray::perf {
namespace {

void buildAccel(benchmark::State& state, const TriangleMesh& mesh, BuildQuality quality = BuildQuality::Fast) {
    FlushToZeroScope ftz;
    BvhBuildConfig config = SceneAccel<8>::defaultConfig();
    config.quality = quality;
    size_t bytes = 0;
    auto geometry = std::make_shared<const SceneGeometry>(mesh);
    for (auto _ : state) {
        ftz.run([&] {
            SceneAccel<8> accel(geometry, config);
            bytes = accel.bytes();
            benchmark::DoNotOptimize(bytes);
        });
    }
    double triangles = double(mesh.triangleCount());
    state.counters["triangles"] = triangles;
    state.counters["triangles/s"] =
        benchmark::Counter(triangles * double(state.iterations()), benchmark::Counter::kIsRate);
    state.counters["MB"] = double(bytes) / 1e6;
}

/// 20 * 4^s triangles: 5,120 to 1,310,720.
void buildIcosphere(benchmark::State& state) {
    const TriangleMesh mesh = makeIcosphere(int(state.range(0)));
    buildAccel(state, mesh);
}
BENCHMARK(buildIcosphere)
    ->Name("bvhBuild/icosphere/subdivisions")
    ->DenseRange(4, 8)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

/// 2 * segments * segments / 2 triangles: 10,000 to 1,000,000.
void buildTorus(benchmark::State& state) {
    const int segments = int(state.range(0));
    const TriangleMesh mesh = makeTorus(1.0f, 0.3f, segments, segments / 2);
    buildAccel(state, mesh);
}
BENCHMARK(buildTorus)
    ->Name("bvhBuild/torus/majorSegments")
    ->Arg(100)
    ->Arg(316)
    ->Arg(1000)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

void buildShared(benchmark::State& state, std::filesystem::path file, BuildQuality quality) {
    buildAccel(state, cachedMesh(file), quality);
}

[[maybe_unused]] const bool registerSharedMeshes = [] {
    for (const char* relative : kSharedMeshes)
        if (auto file = sharedMeshPath(relative))
            for (BuildQuality quality : {BuildQuality::Fast, BuildQuality::High})
                benchmark::RegisterBenchmark(("bvhBuild/shared/" + file->filename().string() +
                                              (quality == BuildQuality::High ? "/high" : ""))
                                                 .c_str(),
                                             buildShared, *file, quality)
                    ->Unit(benchmark::kMillisecond)
                    ->UseRealTime();
    return true;
}();

} // namespace
} // namespace wideray::perf
