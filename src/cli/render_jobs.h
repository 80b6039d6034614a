#pragma once
// What the render command renders: its arguments, scene files loaded with their tracers, the frames of
// each scene (one, or an animation's), where each image goes and the line printed for it. Shared by the
// single-process render and the distributed one (render_distributed.cpp).
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "backends/tracer.h"
#include "cli/commands.h"
#include "core/image.h"
#include "core/scene.h"
#include "geometry/scene_geometry.h"
#include "io/scene_parser.h"
#include "render/render_options.h"

namespace wideray::cli {

struct RenderArgs {
    std::vector<std::string> scenes;
    std::string output;
    std::string size;
    int spp = 0;
    std::string aov = "color";
    std::string backend = "wideray";
    std::string shadingOrder = "material";
    std::string integrator;  ///< empty: the scene's
    std::string frames;      ///< empty: the scene's animation
    bool compareBackends = false;
    EngineOptions engine;
};

/// The tracer a backend builds, what its build is called in the report ("BVH8") and the engine that
/// traces.
struct BackendTracer {
    std::unique_ptr<Tracer> tracer;
    std::string accelName, engine;
};

BackendTracer buildTracer(const RenderArgs& args, const std::string& backendName,
                          std::shared_ptr<const SceneGeometry> geometry);

/// A scene file loaded, with the geometry and tracer its frames are rendered with.
struct LoadedScene {
    SceneDescription scene;
    std::shared_ptr<const SceneGeometry> geometry;
    BackendTracer built;
    double buildSeconds = 0;
};

LoadedScene loadForRender(const RenderArgs& args, const std::string& file);

/// The frames to render of a scene whose animation covers `range` (none: a still scene, one frame
/// without a number), --frames choosing among them. Throws InputError for --frames on a still scene or
/// outside the animation's range.
std::vector<std::optional<int>> framesToRender(const RenderArgs& args, const std::string& file,
                                               const std::optional<FrameRange>& range);

/// The render options the arguments ask for.
RenderOptions renderOptions(const RenderArgs& args, const std::string& label);

/// "scene.json", or "scene.json frame 12".
std::string frameLabel(const std::string& file, std::optional<int> frame);

/// Where a frame's image goes: -o's file (FILE_0012.EXT for frame 12 of an animation), or in -o's
/// folder (an existing folder, or a path without extension), else in out/: NAME.png, NAME_AOV.png,
/// NAME_0012.png.
std::filesystem::path outputPath(const RenderArgs& args, const std::filesystem::path& scene, std::optional<int> frame);

/// Writes the image whole or not at all (depths scaled to [0, 1] for 8-bit formats).
void writeFrame(Image& image, const std::filesystem::path& path, Aov aov);

/// The line printed for a rendered frame.
struct FrameLine {
    std::string label;
    int width = 0, height = 0, samplesPerPixel = 0;
    uint64_t triangles = 0;
    std::string accelName, engine;
    double buildSeconds = 0;
    RenderStats stats;
    int ranks = 0;  ///< > 0: rendered by this many MPI ranks
    std::filesystem::path output;
};
void printFrameLine(const FrameLine& line, Aov aov);

/// Renders the batch on the ranks of the MPI job this process belongs to (mpirun -np N wideray render
/// ...): rank 0 writes every image and prints its line; returns this rank's exit code.
int renderWithMpi(const RenderArgs& args);

} // namespace wideray::cli
