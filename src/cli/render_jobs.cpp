#include "cli/render_jobs.h"

#include <chrono>
#include <cstdio>

#include <fmt/core.h>

#include "backends/backend_registry.h"
#include "core/error.h"
#include "io/image_io.h"
#include "io/mesh_framing.h"
#include "io/scene_vocabulary.h"

namespace wideray::cli {

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

LoadedScene loadForRender(const RenderArgs& args, const std::string& file) {
    using Clock = std::chrono::steady_clock;
    LoadedScene loaded;
    // A bare mesh is framed for the image size asked for.
    const auto [width, height] = args.size.empty() ? std::pair{1024, 1024} : parseSize(args.size);
    loaded.scene = loadSceneOrMesh(file, width, height, MeshFraming::Showcase);
    for (const std::string& warning : loaded.scene.warnings) fmt::print(stderr, "warning: {}\n", warning);
    for (const auto& [name, integrator] : kIntegrators)
        if (name == args.integrator) loaded.scene.render.integrator = integrator;
    const auto start = Clock::now();
    loaded.geometry = std::make_shared<const SceneGeometry>(loaded.scene,
                                                            instancingFor(args.engine.instancing, {args.engine.accel}));
    loaded.built = buildTracer(args, args.backend, loaded.geometry);
    loaded.buildSeconds = std::chrono::duration<double>(Clock::now() - start).count();
    return loaded;
}

namespace {

/// --frames FIRST or FIRST-LAST.
FrameRange parseFrames(const std::string& text) {
    int first = 0, last = 0;
    char dash = 0, extra = 0;
    const int n = std::sscanf(text.c_str(), "%d%c%d%c", &first, &dash, &last, &extra);
    if (n == 1) last = first;
    if (!(n == 1 || (n == 3 && dash == '-')) || first < 0 || last < first || last > kLastFrame)
        throw InputError("--frames", "", "expected FIRST or FIRST-LAST with 0 <= FIRST <= LAST <= " +
                                             std::to_string(kLastFrame) + ", got '" + text + "'");
    return {first, last};
}

} // namespace

std::vector<std::optional<int>> framesToRender(const RenderArgs& args, const std::string& file,
                                               const std::optional<FrameRange>& range) {
    if (!range && !args.frames.empty())
        throw InputError(file, "", "--frames " + args.frames + " asks for frames, but the scene has no \"animation\"");
    if (!range) return {std::nullopt};
    const FrameRange chosen = args.frames.empty() ? *range : parseFrames(args.frames);
    if (chosen.first < range->first || chosen.last > range->last)
        throw InputError(file, "", fmt::format("--frames {} asks for frames outside the animation's {}-{}", args.frames,
                                               range->first, range->last));
    std::vector<std::optional<int>> frames;
    for (int f = chosen.first; f <= chosen.last; ++f) frames.push_back(f);
    return frames;
}

RenderOptions renderOptions(const RenderArgs& args, const std::string& label) {
    RenderOptions options;
    if (!args.size.empty()) std::tie(options.width, options.height) = parseSize(args.size);
    options.samplesPerPixel = args.spp;
    options.aov = args.aov == "normal" ? Aov::Normal
                  : args.aov == "depth" ? Aov::Depth
                  : args.aov == "cost"  ? Aov::Cost
                                        : Aov::Color;
    options.shadingOrder = args.shadingOrder == "ray" ? ShadingOrder::Ray : ShadingOrder::Material;
    options.progress = true;
    options.label = label;
    return options;
}

std::string frameLabel(const std::string& file, std::optional<int> frame) {
    return frame ? fmt::format("{} frame {}", file, *frame) : file;
}

std::filesystem::path outputPath(const RenderArgs& args, const std::filesystem::path& scene, std::optional<int> frame) {
    const std::string suffix = frame ? fmt::format("_{:04d}", *frame) : "";
    const std::string name = scene.stem().string() + (args.aov == "color" ? "" : "_" + args.aov) + suffix + ".png";
    if (args.output.empty()) return std::filesystem::path("out") / name;
    // -o names a file when it has an extension and is not a folder, and when there is one scene.
    const std::filesystem::path output(args.output);
    const bool folder = std::filesystem::is_directory(output) || !output.has_extension() || args.output.back() == '/';
    if (args.scenes.size() == 1 && !folder) {
        return suffix.empty() ? output
                              : output.parent_path() / (output.stem().string() + suffix + output.extension().string());
    }
    return output / name;
}

void writeFrame(Image& image, const std::filesystem::path& path, Aov aov) {
    // 8-bit formats cannot hold depths, so those are scaled to [0, 1] by the largest depth.
    if (aov == Aov::Depth && !isFloatFormat(path)) {
        float maxDepth = 0.0f;
        for (float d : image.pixels) maxDepth = std::max(maxDepth, d);
        if (maxDepth > 0.0f)
            for (float& d : image.pixels) d /= maxDepth;
    }
    writeImage(image, path, aov == Aov::Color);
}

void printFrameLine(const FrameLine& line, Aov aov) {
    fmt::print("{}: {}x{}, {} spp, {} triangles, {} build {:.1f} ms, render {:.1f} ms{}, {} rays, {:.2f} Mrays/s ({}) -> {}\n",
               line.label, line.width, line.height, line.samplesPerPixel, line.triangles, line.accelName,
               line.buildSeconds * 1e3, line.stats.seconds * 1e3,
               line.ranks > 0 ? fmt::format(" on {} rank{}", line.ranks, line.ranks == 1 ? "" : "s") : "",
               line.stats.totalRays(), line.stats.mraysPerSecond(), line.engine, line.output.string());
    if (aov == Aov::Cost) fmt::print("  cost heatmap: max {} nodes + primitives per pixel\n", line.stats.maxCost);
    std::fflush(stdout);
}

} // namespace wideray::cli
