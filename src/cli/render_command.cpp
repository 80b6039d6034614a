// wideray render: renders scene files in a batch; a scene that fails is reported and skipped.
#include <chrono>
#include <cstdio>
#include <exception>
#include <filesystem>

#include <fmt/core.h>
#include <tbb/global_control.h>

#include "backends/backend_registry.h"
#include "cli/commands.h"
#include "core/error.h"
#include "core/fp_mode.h"
#include "io/image_io.h"
#include "io/mesh_framing.h"
#include "io/scene_vocabulary.h"
#include "render/image_difference.h"
#include "render/renderer.h"

namespace wideray::cli {
namespace {

struct RenderArgs {
    std::vector<std::string> scenes;
    std::string output;
    std::string size;
    int spp = 0;
    std::string aov = "color";
    std::string backend = "wideray";
    std::string shadingOrder = "material";
    std::string integrator;  ///< empty: the scene's
    bool compareBackends = false;
    EngineOptions engine;
};

Aov parseAov(const std::string& name) {
    if (name == "normal") return Aov::Normal;
    if (name == "depth") return Aov::Depth;
    if (name == "cost") return Aov::Cost;
    return Aov::Color;
}

std::filesystem::path outputPath(const RenderArgs& args, const std::filesystem::path& scene) {
    std::string name = scene.stem().string() + (args.aov == "color" ? "" : "_" + args.aov) + ".png";
    if (args.output.empty()) return std::filesystem::path("out") / name;
    if (args.scenes.size() == 1 && !std::filesystem::is_directory(args.output)) return args.output;
    return std::filesystem::path(args.output) / name;
}

/// 8-bit formats cannot hold depths, so those are scaled to [0, 1] by the largest depth.
void normalizeDepth(Image& image, const std::filesystem::path& path) {
    std::string ext = path.extension().string();
    if (ext == ".exr" || ext == ".hdr" || ext == ".pfm") return;
    float maxDepth = 0.0f;
    for (float d : image.pixels) maxDepth = std::max(maxDepth, d);
    if (maxDepth > 0.0f)
        for (float& d : image.pixels) d /= maxDepth;
}

/// The tracer the backend builds, what its build is called in the report ("BVH8") and the engine
/// that traces.
struct BackendTracer {
    std::unique_ptr<Tracer> tracer;
    std::string accelName, engine;
};

BackendTracer buildTracer(const RenderArgs& args, const std::string& backendName,
                          std::shared_ptr<const SceneGeometry> geometry) {
    StructureOptions options;
    options.accel = args.engine.accel;
    options.bvhWidth = args.engine.bvhWidth;
    options.quality = args.engine.quality;
    std::shared_ptr<const Structure> structure = findBackend(backendName).build(std::move(geometry), options);
    // --kernel, --isa and --bvh-width choose among our kernels; Embree traces with its own choice.
    std::unique_ptr<Tracer> tracer = structure->tracer(backendName == "wideray" ? kernelChoice(args.engine) : KernelChoice{});
    std::string engine = tracer->description();
    return {std::move(tracer), structure->name(), engine};
}

void renderOne(const RenderArgs& args, const std::string& sceneFile) {
    using Clock = std::chrono::steady_clock;
    Scene scene = loadSceneOrMesh(sceneFile, 1024, 1024);
    for (const auto& [name, integrator] : kIntegrators)
        if (name == args.integrator) scene.render.integrator = integrator;
    auto start = Clock::now();
    auto geometry = std::make_shared<const SceneGeometry>(scene, instancingFor(args.engine.instancing, {args.engine.accel}));
    BackendTracer built = buildTracer(args, args.backend, geometry);
    double buildSeconds = std::chrono::duration<double>(Clock::now() - start).count();

    RenderOptions options;
    if (!args.size.empty()) std::tie(options.width, options.height) = parseSize(args.size);
    options.samplesPerPixel = args.spp;
    options.aov = parseAov(args.aov);
    options.shadingOrder = args.shadingOrder == "ray" ? ShadingOrder::Ray : ShadingOrder::Material;
    options.progress = true;
    options.label = sceneFile;
    RenderStats stats;
    Image image = render(scene, *built.tracer, options, stats);

    std::filesystem::path out = outputPath(args, sceneFile);
    if (options.aov == Aov::Depth) normalizeDepth(image, out);
    writeImage(image, out, options.aov == Aov::Color);
    fmt::print("{}: {}x{}, {} spp, {} triangles, {} build {:.1f} ms, render {:.1f} ms, {} rays, "
               "{:.2f} Mrays/s ({}) -> {}\n",
               sceneFile, image.width, image.height,
               args.spp > 0 ? args.spp : scene.image.samplesPerPixel, geometry->triangleCount(), built.accelName,
               buildSeconds * 1e3, stats.seconds * 1e3, stats.totalRays(),
               stats.mraysPerSecond(), built.engine, out.string());
    if (options.aov == Aov::Cost) fmt::print("  cost heatmap: max {} nodes + primitives per pixel\n", stats.maxCost);
    if (std::string report = built.tracer->statsReport(); !report.empty()) fmt::print("  {}\n", report);
    if (args.compareBackends) {
        BackendTracer other = buildTracer(args, args.backend == "embree" ? "wideray" : "embree", geometry);
        RenderStats otherStats;
        Image otherImage = render(scene, *other.tracer, options, otherStats);
        if (options.aov == Aov::Depth) normalizeDepth(otherImage, out);
        ImageDifference d = compareImages(image, otherImage, 1.0f / 255.0f);
        fmt::print("  vs {} (render {:.1f} ms, {:.2f} Mrays/s): mean |difference| {:.6f}, max {:.4f}, {} of {} pixels "
                   "differ by more than 1/255\n",
                   other.engine, otherStats.seconds * 1e3, otherStats.mraysPerSecond(), d.meanAbsolute, d.maxAbsolute,
                   d.pixelsOver, d.pixels);
    }
    std::fflush(stdout);
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
                    "Output image (format from its extension: png, exr, jpg, tif, ...); with several scenes, "
                    "a folder. Default: out/SCENE.png (out/SCENE_AOV.png for other AOVs)");
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
    cmd->add_flag("--compare-backends", args->compareBackends,
                  "Also render through the other backend and print pixel difference statistics");
    addEngineOptions(*cmd, args->engine);
    cmd->callback([args, &exitCode] {
        FlushToZeroScope ftz;
        std::optional<tbb::global_control> threads;
        if (args->engine.threads > 0)
            threads.emplace(tbb::global_control::max_allowed_parallelism, size_t(args->engine.threads));
        int failed = 0;
        for (const std::string& scene : args->scenes) {
            try {
                renderOne(*args, scene);
            } catch (const std::exception& e) {
                ++failed;
                fmt::print(stderr, "error: {}\n", e.what());
            }
        }
        if (failed > 0) {
            fmt::print(stderr, "{} of {} scenes failed\n", failed, args->scenes.size());
            exitCode = 1;
        }
    });
}

} // namespace wideray::cli
