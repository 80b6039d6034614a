// wideray render: renders scene files in a batch (each frame of an animated scene); a scene that fails
// is reported and skipped. Under mpirun the batch is shared by the ranks (render_distributed.cpp).
#include <cstdio>
#include <exception>

#include <fmt/core.h>
#include <tbb/global_control.h>

#include "backends/backend_registry.h"
#include "cli/commands.h"
#include "cli/render_jobs.h"
#include "core/camera_path.h"
#include "core/fp_mode.h"
#include "io/scene_vocabulary.h"
#include "mpi/launch.h"
#include "render/image_difference.h"
#include "render/renderer.h"

namespace wideray::cli {
namespace {

/// Renders each frame of a scene file in this process, loading the scene and building its tracer once.
void renderScene(const RenderArgs& args, const std::string& sceneFile) {
    LoadedScene loaded = loadForRender(args, sceneFile);
    SceneDescription& scene = loaded.scene;
    const std::optional<FrameRange> range =
        scene.animation ? std::optional<FrameRange>({scene.animation->firstFrame, scene.animation->lastFrame}) : std::nullopt;
    std::optional<BackendTracer> other;
    if (args.compareBackends) other = buildTracer(args, args.backend == "embree" ? "wideray" : "embree", loaded.geometry);
    for (const std::optional<int> frame : framesToRender(args, sceneFile, range)) {
        if (frame) scene.camera = cameraAtFrame(*scene.animation, *frame);
        const RenderOptions options = renderOptions(args, frameLabel(sceneFile, frame));
        FrameLine line;
        Image image = render(scene, *loaded.built.tracer, options, line.stats);
        line.label = options.label;
        line.width = image.width;
        line.height = image.height;
        line.samplesPerPixel = args.spp > 0 ? args.spp : scene.image.samplesPerPixel;
        line.triangles = loaded.geometry->triangleCount();
        line.accelName = loaded.built.accelName;
        line.engine = loaded.built.engine;
        line.buildSeconds = loaded.buildSeconds;
        line.output = outputPath(args, sceneFile, frame);
        Image written = other ? image : Image{};
        writeFrame(image, line.output, options.aov);
        printFrameLine(line, options.aov);
        if (std::string report = loaded.built.tracer->statsReport(); !report.empty()) fmt::print("  {}\n", report);
        if (other) {
            RenderStats otherStats;
            Image otherImage = render(scene, *other->tracer, options, otherStats);
            ImageDifference d = compareImages(written, otherImage, 1.0f / 255.0f);
            fmt::print("  vs {} (render {:.1f} ms, {:.2f} Mrays/s): mean |difference| {:.6f}, max {:.4f}, {} of {} pixels "
                       "differ by more than 1/255\n",
                       other->engine, otherStats.seconds * 1e3, otherStats.mraysPerSecond(), d.meanAbsolute,
                       d.maxAbsolute, d.pixelsOver, d.pixels);
        }
        std::fflush(stdout);
    }
}

/// Renders the batch in this process; returns how many scenes failed.
size_t renderHere(const RenderArgs& args) {
    size_t failed = 0;
    for (const std::string& scene : args.scenes) {
        try {
            renderScene(args, scene);
        } catch (const std::exception& e) {
            ++failed;
            fmt::print(stderr, "error: {}\n", e.what());
        }
    }
    return failed;
}

std::vector<std::string> backendNames() {
    std::vector<std::string> names;
    for (const Backend& b : backends()) names.push_back(b.name);
    return names;
}

} // namespace

void addRenderCommand(CLI::App& app, int& exitCode) {
    auto args = std::make_shared<RenderArgs>();
    CLI::App* cmd = app.add_subcommand("render", "Render scene files (or bare meshes) to images");
    cmd->add_option("scenes", args->scenes, "Scene files (.json, see docs/scene-format.md) or meshes (.obj, .ply, "
                                            ".gltf, .glb, framed by the rule in docs/performance.md)")
        ->required();
    cmd->add_option("-o,--output", args->output,
                    "Output image (format from its extension: png, exr, jpg, tif, ...; frame 12 of an animation: "
                    "FILE_0012.EXT), or a folder (with several scenes, or a path without extension). Default: "
                    "out/SCENE.png (out/SCENE_AOV.png for other AOVs, out/SCENE_0012.png for frames)");
    cmd->add_option("--size", args->size, "Image size WxH, overriding the scene's");
    cmd->add_option("--spp", args->spp, "Samples per pixel, overriding the scene's")->check(CLI::Range(1, 1 << 16));
    cmd->add_option("--aov", args->aov,
                    "What to write: color, normal (n * 0.5 + 0.5), depth (hit distance; scaled to [0,1] in "
                    "8-bit formats) or cost (heatmap of BVH nodes + primitives the chosen kernel visited per pixel)")
        ->check(CLI::IsMember({"color", "normal", "depth", "cost"}))
        ->capture_default_str();
    cmd->add_option("--backend", args->backend,
                    "Who traces the rays: wideray (our kernels) or embree (Intel Embree, with its default BVH "
                    "and its widest native packets; --kernel, --isa and --bvh-width do not apply)")
        ->check(CLI::IsMember(backendNames()))
        ->capture_default_str();
    cmd->add_option("--integrator", args->integrator,
                    "How light is gathered, overriding the scene's render.integrator: whitted or path")
        ->check(CLI::IsMember([] {
            std::vector<std::string> names;
            for (const auto& [name, integrator] : kIntegrators) names.push_back(name);
            return names;
        }()));
    cmd->add_option("--shading-order", args->shadingOrder,
                    "Order in which each bounce's hits are shaded: material (grouped by material) or ray (as traced); "
                    "the images agree up to the rounding of the pixel sums")
        ->check(CLI::IsMember({"material", "ray"}))
        ->capture_default_str();
    cmd->add_option("--frames", args->frames,
                    "Frames of the scenes' animations to render, FIRST or FIRST-LAST (default: the animation's "
                    "range); each is written as NAME_0012.png");
    cmd->add_flag("--compare-backends", args->compareBackends,
                  "Also render through the other backend and print pixel difference statistics (not under mpirun)");
    addEngineOptions(*cmd, args->engine);
    cmd->callback([args, &exitCode] {
        FlushToZeroScope ftz;
        ftz.run([&] {
            std::optional<tbb::global_control> threads;
            if (args->engine.threads > 0)
                threads.emplace(tbb::global_control::max_allowed_parallelism, size_t(args->engine.threads));
            if (launchedRanks() > 0) {
#ifdef WIDERAY_HAVE_MPI
                exitCode = renderWithMpi(*args);
#else
                fmt::print(stderr, "error: wideray was started by mpirun, but this build has no MPI support (install "
                                   "libopenmpi-dev and rebuild; without mpirun, render runs in one process)\n");
                exitCode = 1;
#endif
                return;
            }
            if (const size_t failed = renderHere(*args); failed > 0) {
                fmt::print(stderr, "{} of {} scenes failed\n", failed, args->scenes.size());
                exitCode = 1;
            }
        });
    });
}

} // namespace wideray::cli
