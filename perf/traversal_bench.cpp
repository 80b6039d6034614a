// Closest-hit traversal of an 8-wide BVH, one kernel at a time on one thread: the scalar reference
// and every kernel of the best ISA this CPU has (single, packet4/8/16, stream, drst), on the primary and
// diffuse rays of `wideray bench` (core/bench_rays.h) for the Stanford bunny, or a generated torus
// when the shared meshes are absent.
#include <benchmark/benchmark.h>

#include <memory>
#include <string>
#include <vector>

#include "render/bench_rays.h"
#include "core/fp_mode.h"
#include "io/mesh_framing.h"
#include "io/mesh_generators.h"
#include "accel/scene_accel.h"
#include "kernels/isa_kernels.h"
#include "kernels/reference_kernel.h"
#include "backends/tracer_factory.h"
#include "perf_inputs.h"

namespace wideray::perf {
namespace {

constexpr int kImageSize = 512;  // 512 x 512 primary rays
constexpr const char* kBunny = "stanford-bunny/bun_zipper.ply";

struct TraversalInputs {
    std::unique_ptr<SceneAccel<8>> accel;
    BenchRays rays;
};

std::string inputName() { return sharedMeshPath(kBunny) ? "bun_zipper" : "torus_160k"; }

/// Built on first use, so that listing or filtering the benchmarks loads nothing.
const TraversalInputs& inputs() {
    static const TraversalInputs built = [] {
        auto bunny = sharedMeshPath(kBunny);
        Scene scene = bunny ? sceneFromMesh(*bunny, kImageSize, kImageSize)
                            : sceneFromMesh(makeTorus(1.0f, 0.3f, 400, 200), kImageSize, kImageSize);
        TriangleMesh world = flattenTriangles(scene);
        TracerConfig config;
        BuiltTracer tracer = buildWiderayTracer(scene, world, config);
        TraversalInputs in;
        in.rays = makeBenchRays(scene, world, *tracer.tracer, kImageSize, kImageSize);
        in.accel = std::make_unique<SceneAccel<8>>(world, userGeometries(scene));
        return in;
    }();
    return built;
}

void traverse(benchmark::State& state, KernelSet<8> kernel, RayKind kind) {
    enableFlushToZero();
    const TraversalInputs& in = inputs();
    const std::vector<Ray>& rays = in.rays.of(kind);
    std::vector<Hit> hits(rays.size());
    SceneView<8> view = in.accel->view();
    for (auto _ : state) {
        kernel.intersect(view, rays.data(), hits.data(), rays.size(), nullptr);
        benchmark::DoNotOptimize(hits.data());
    }
    state.counters["rays/s"] = benchmark::Counter(double(rays.size()) * double(state.iterations()),
                                                  benchmark::Counter::kIsRate);
}

[[maybe_unused]] const bool registerKernels = [] {
    std::vector<std::pair<KernelSet<8>, std::string>> kernels{
        {{"scalar", &reference::intersect<8>, &reference::occluded<8>}, "scalar"}};
    Isa isa = bestIsa();
    IsaKernelTable<8> table = kernelTable<8>(isa);
    for (const KernelSet<8>& k : {table.single, table.packet4, table.packet8, table.packet16, table.stream, table.drst})
        if (k.intersect) kernels.push_back({k, std::string(k.name) + "_" + isaName(isa)});
    for (RayKind kind : {RayKind::Primary, RayKind::Diffuse})
        for (const auto& [kernel, name] : kernels)
            benchmark::RegisterBenchmark(("traversal/" + inputName() + "/" + rayKindName(kind) + "/" + name).c_str(),
                                         traverse, kernel, kind)
                ->Unit(benchmark::kMillisecond)
                ->UseRealTime();
    return true;
}();

} // namespace
} // namespace wideray::perf
