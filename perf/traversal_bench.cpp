// Traversal of the 8-wide BVH (and of the 16-wide one, as bvh16_<kernel>), one kernel at a time on one
// thread: the scalar reference and every kernel of the best ISA this CPU has (the rows of
// kernels/kernel_registry.h), on the primary, shadow (any-hit), diffuse and bounce rays of `wideray
// bench` (render/bench_rays.h) for the Stanford bunny, or a generated torus when the shared meshes are
// absent. WIDERAY_TRAVERSAL_INPUT names another scene file or mesh (an interior scene, say:
// `WIDERAY_TRAVERSAL_INPUT=scenes/sponza_interior.json wideray_perf`); WIDERAY_TRAVERSAL_QUALITY=high
// traces the spatial-split build instead of the fast one.
#include <benchmark/benchmark.h>

#include <cstdlib>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "render/bench_rays.h"
#include "core/fp_mode.h"
#include "io/mesh_framing.h"
#include "io/mesh_generators.h"
#include "backends/wideray_structure.h"
#include "kernels/kernel_registry.h"
#include "perf_inputs.h"

namespace wideray::perf {
namespace {

constexpr int kImageSize = 512;  // 512 x 512 primary rays
constexpr const char* kBunny = "stanford-bunny/bun_zipper.ply";

struct TraversalInputs {
    SceneDescription scene;
    std::shared_ptr<const WideBvhStructure<8>> bvh;
    BenchRays rays;
};

const char* chosenInput() { return std::getenv("WIDERAY_TRAVERSAL_INPUT"); }

BuildQuality chosenQuality() {
    const char* quality = std::getenv("WIDERAY_TRAVERSAL_QUALITY");
    return quality && std::string(quality) == "high" ? BuildQuality::High : BuildQuality::Fast;
}

std::string inputName() {
    if (const char* input = chosenInput()) return std::filesystem::path(input).stem().string();
    return sharedMeshPath(kBunny) ? "bun_zipper" : "torus_160k";
}

/// Built on first use, so that listing or filtering the benchmarks loads nothing.
const TraversalInputs& inputs() {
    static const TraversalInputs built = [] {
        auto bunny = sharedMeshPath(kBunny);
        SceneDescription scene = chosenInput() ? loadSceneOrMesh(chosenInput(), kImageSize, kImageSize)
                      : bunny       ? sceneFromMesh(*bunny, kImageSize, kImageSize)
                                    : sceneFromMesh(makeTorus(1.0f, 0.3f, 400, 200), kImageSize, kImageSize);
        TraversalInputs in;
        in.scene = scene;
        in.bvh = std::make_shared<const WideBvhStructure<8>>(std::make_shared<const SceneGeometry>(scene),
                                                             chosenQuality());
        in.rays = makeBenchRays(scene, *in.bvh->tracer({"scalar"}), kImageSize, kImageSize);
        return in;
    }();
    return built;
}

/// The BVH of width N over the inputs' scene (the 8-wide one is theirs).
template <int N>
const WideBvhStructure<N>& bvhOfWidth() {
    if constexpr (N == 8) {
        return *inputs().bvh;
    } else {
        static const WideBvhStructure<N> built(std::make_shared<const SceneGeometry>(inputs().scene), chosenQuality());
        return built;
    }
}

template <int N>
void traverse(benchmark::State& state, Kernel<N> kernel, RayKind kind) {
    enableFlushToZero();
    const TraversalInputs& in = inputs();
    const std::vector<Ray>& rays = in.rays.of(kind);
    std::vector<Hit> hits(rays.size());
    std::vector<uint8_t> occluded(rays.size());
    SceneView<N> view = bvhOfWidth<N>().accel().view();
    for (auto _ : state) {
        if (kind == RayKind::Shadow) kernel.occluded(view, rays.data(), occluded.data(), rays.size(), nullptr);
        else kernel.intersect(view, rays.data(), hits.data(), rays.size(), nullptr);
        benchmark::DoNotOptimize(hits.data());
        benchmark::DoNotOptimize(occluded.data());
    }
    state.counters["rays/s"] = benchmark::Counter(double(rays.size()) * double(state.iterations()),
                                                  benchmark::Counter::kIsRate);
}

template <int N>
void registerKernels(const std::string& prefix) {
    std::vector<std::pair<Kernel<N>, std::string>> kernels;
    const Isa isa = bestIsa();
    for (const Kernel<N>& k : kernelTable<N>(isa).rows)
        if (k.available()) kernels.push_back({k, prefix + k.name + "_" + isaName(isa)});
    for (RayKind kind : {RayKind::Primary, RayKind::Shadow, RayKind::Diffuse, RayKind::Bounce})
        for (const auto& [kernel, name] : kernels)
            benchmark::RegisterBenchmark(("traversal/" + inputName() + "/" + rayKindName(kind) + "/" + name).c_str(),
                                         traverse<N>, kernel, kind)
                ->Unit(benchmark::kMillisecond)
                ->UseRealTime();
}

[[maybe_unused]] const bool registered = [] {
    registerKernels<8>("");
    registerKernels<16>("bvh16_");
    return true;
}();

} // namespace
} // namespace wideray::perf
