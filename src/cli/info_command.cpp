// wideray info: the shape and cost of the wide BVHs of a scene or mesh, and the ISA in use.
#include <chrono>
#include <exception>

#include <fmt/core.h>

#include "cli/commands.h"
#include "accel/bvh_stats.h"
#include "core/fp_mode.h"
#include "io/mesh_framing.h"
#include "accel/scene_accel.h"
#include "backends/tracer_factory.h"

namespace wideray::cli {
namespace {

template <int N>
void printBvh(const Scene& scene, const TriangleMesh& world) {
    auto start = std::chrono::steady_clock::now();
    SceneAccel<N> accel(world, userGeometries(scene));
    double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    BvhStats s = wideBvhStats(accel.triangleBvh(), SceneAccel<N>::defaultConfig());
    double bytesPerTriangle = world.triangles.empty() ? 0.0 : double(accel.bytes()) / double(world.triangles.size());
    fmt::print("BVH{}: {} inner nodes, {} leaves ({} blocks of {} triangles), depth {}, SAH cost {:.2f}, "
               "{:.1f} bytes/triangle, build {:.1f} ms (binned SAH {:.1f} ms + collapse {:.1f} ms)\n",
               N, s.innerNodes, s.leaves, s.leafItems, kBlockSize, s.depth, s.sahCost, bytesPerTriangle,
               seconds * 1e3, accel.timings().binarySeconds * 1e3, accel.timings().collapseSeconds * 1e3);
}

} // namespace

void addInfoCommand(CLI::App& app, int& exitCode) {
    auto files = std::make_shared<std::vector<std::string>>();
    auto isa = std::make_shared<std::string>("auto");
    CLI::App* cmd = app.add_subcommand("info", "Print triangles, BVH shape, SAH cost, memory and build time of "
                                               "scenes or meshes, and the detected and chosen ISA");
    cmd->add_option("files", *files, "Scene files or meshes")->required();
    cmd->add_option("--isa", *isa, "The ISA to report as chosen: sse42, avx2, avx512 or auto")
        ->check(CLI::IsMember({"sse42", "avx2", "avx512", "auto"}))
        ->capture_default_str();
    cmd->callback([files, isa, &exitCode] {
        FlushToZeroScope ftz;
        Isa chosen = *isa == "auto" ? bestIsa() : *parseIsa(*isa);
        fmt::print("CPU: {}; detected ISA: {}; chosen ISA: {}{}\n", cpuModelName(), isaName(bestIsa()),
                   isaName(chosen), cpuSupports(chosen) ? "" : " (NOT supported by this CPU)");
        if (!cpuSupports(chosen)) exitCode = 1;
        for (const std::string& file : *files) {
            try {
                Scene scene = loadSceneOrMesh(file);
                TriangleMesh world = flattenTriangles(scene);
                size_t dropped = 0;
                for (const TriangleMesh& m : scene.meshes) dropped += m.droppedDegenerate;
                fmt::print("{}: {} triangles ({} zero-area dropped), {} spheres, {} meshes, {} instances\n", file,
                           world.triangles.size(), dropped, scene.spheres.size(), scene.meshes.size(),
                           scene.instances.size());
                printBvh<4>(scene, world);
                printBvh<8>(scene, world);
            } catch (const std::exception& e) {
                fmt::print(stderr, "error: {}\n", e.what());
                exitCode = 1;
            }
        }
    });
}

} // namespace wideray::cli
