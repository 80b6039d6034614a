// wideray info: the shape, memory and build time of a scene's acceleration structures, and the ISA in use.
#include <exception>

#include <fmt/core.h>
#include <fmt/format.h>

#include "backends/backend_registry.h"
#include "cli/commands.h"
#include "core/fp_mode.h"
#include "io/mesh_framing.h"

namespace wideray::cli {

void addInfoCommand(CLI::App& app, int& exitCode) {
    auto files = std::make_shared<std::vector<std::string>>();
    auto isa = std::make_shared<std::string>("auto");
    auto quality = std::make_shared<std::string>("fast");
    CLI::App* cmd = app.add_subcommand("info", "Print triangles, the shape, memory and build time of each "
                                               "acceleration structure (--accel; BVH SAH cost) of scenes or meshes, and "
                                               "the detected and chosen ISA");
    cmd->add_option("files", *files, "Scene files or meshes")->required();
    cmd->add_option("--isa", *isa, "The ISA to report as chosen: sse42, avx2, avx512 or auto")
        ->check(CLI::IsMember({"sse42", "avx2", "avx512", "auto"}))
        ->capture_default_str();
    addQualityOption(*cmd, *quality);
    auto instancing = std::make_shared<std::string>("auto");
    addInstancingOption(*cmd, *instancing);
    auto accel = std::make_shared<std::vector<std::string>>();
    cmd->add_option("--accel", *accel, accelHelp(true) + fmt::format(" (default: {})", fmt::join(wideBvhNames(), ",")))
        ->check(CLI::IsMember(accelNames()))
        ->delimiter(',');
    cmd->callback([files, isa, quality, accel, instancing, &exitCode] {
        FlushToZeroScope ftz;
        ftz.run([&] {
            Isa chosen = *isa == "auto" ? bestIsa() : *parseIsa(*isa);
            fmt::print("CPU: {}; detected ISA: {}; chosen ISA: {}{}\n", cpuModelName(), isaName(bestIsa()),
                       isaName(chosen), cpuSupports(chosen) ? "" : " (NOT supported by this CPU)");
            if (!cpuSupports(chosen)) exitCode = 1;
            for (const std::string& file : *files) {
                try {
                    SceneDescription scene = loadSceneOrMesh(file);
                    for (const std::string& warning : scene.warnings) fmt::print(stderr, "warning: {}\n", warning);
                    const std::vector<std::string> accels = accel->empty() ? wideBvhNames() : *accel;
                    auto geometry = std::make_shared<const SceneGeometry>(scene, instancingFor(*instancing, accels));
                    size_t dropped = 0;
                    for (const TriangleMesh& m : scene.meshes) dropped += m.droppedDegenerate;
                    fmt::print("{}: {} triangles ({} zero-area dropped), {} spheres, {} meshes, {} instances\n", file,
                               geometry->triangleCount(), dropped, scene.spheres.size(), scene.meshes.size(),
                               scene.instances.size());
                    const Backend& ours = findBackend("wideray");
                    for (const std::string& name : accels) {
                        StructureOptions options;
                        options.accel = name;
                        options.quality = *quality;
                        std::shared_ptr<const Structure> structure = ours.build(geometry, options);
                        fmt::print("{}; {:.1f} MB\n", structure->summary(), double(structure->bytes()) / 1e6);
                    }
                } catch (const std::exception& e) {
                    fmt::print(stderr, "error: {}\n", e.what());
                    exitCode = 1;
                }
            }
        });
    });
}

} // namespace wideray::cli
