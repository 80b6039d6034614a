// renderSceneFile (include/wideray/render.h): what `wideray render FILE` does, into memory.
#include "wideray/render.h"

#include <optional>

#include <fmt/core.h>
#include <tbb/global_control.h>

#include "api/mxcsr_scope.h"
#include "backends/wideray_structure.h"
#include "core/error.h"
#include "core/fp_mode.h"
#include "io/mesh_framing.h"
#include "io/scene_vocabulary.h"
#include "render/renderer.h"
#include "wideray/error.h"

namespace wideray {

RenderedImage renderSceneFile(const std::string& path, const RenderRequest& request) {
    if (request.width < 0 || request.height < 0 || request.samplesPerPixel < 0 || request.threads < 0)
        throw Error(fmt::format("renderSceneFile: size {}x{}, {} samples per pixel and {} threads: none may be negative",
                                request.width, request.height, request.samplesPerPixel, request.threads));
    if ((request.width == 0) != (request.height == 0))
        throw Error("renderSceneFile: give both width and height, or neither (the scene's size)");
    try {
        SceneDescription scene = loadSceneOrMesh(path, request.width > 0 ? request.width : 1024,
                                                 request.height > 0 ? request.height : 1024, MeshFraming::Showcase);
        if (!request.integrator.empty()) {
            bool known = false;
            for (const auto& [name, integrator] : kIntegrators)
                if (name == request.integrator) scene.render.integrator = integrator, known = true;
            if (!known)
                throw Error("renderSceneFile: integrator '" + request.integrator + "' is not whitted or path");
        }
        std::optional<tbb::global_control> threads;
        if (request.threads > 0) threads.emplace(tbb::global_control::max_allowed_parallelism, size_t(request.threads));
        MxcsrScope callerMode;  // saved before FlushToZeroScope sets this thread's mode, restored after
        FlushToZeroScope ftz;
        return ftz.run([&]() -> RenderedImage {
            auto geometry = std::make_shared<const SceneGeometry>(scene);
            std::shared_ptr<const Structure> structure = buildWideBvh(geometry, StructureOptions{});
            std::unique_ptr<Tracer> tracer = structure->tracer(KernelChoice{});
            RenderOptions options;
            options.width = request.width;
            options.height = request.height;
            options.samplesPerPixel = request.samplesPerPixel;
            RenderStats stats;
            Image image = render(scene, *tracer, options, stats);
            return {image.width, image.height, std::move(image.pixels)};
        });
    } catch (const InputError& e) {
        throw Error(e.what());
    } catch (const std::length_error& e) {  // more primitives than the structure can address
        throw Error(path + ": " + e.what());
    }
}

} // namespace wideray
