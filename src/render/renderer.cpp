#include "render/renderer.h"

#include <chrono>

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include "render/progress.h"
#include "render/render_memory.h"
#include "render/tile_renderer.h"

namespace wideray {

RenderOptions resolveRenderOptions(const SceneDescription& scene, const RenderOptions& options) {
    RenderOptions resolved = options;
    resolved.width = options.width > 0 ? options.width : scene.image.width;
    resolved.height = options.height > 0 ? options.height : scene.image.height;
    resolved.samplesPerPixel = options.samplesPerPixel > 0 ? options.samplesPerPixel : scene.image.samplesPerPixel;
    if (resolved.tileSize == 0) resolved.tileSize = renderTileSize(scene, resolved.samplesPerPixel);
    return resolved;
}

double renderTiles(const SceneDescription& scene, const Tracer& tracer, const RenderOptions& options, const TileOrder& order,
                   std::span<const TileRect> tiles, Film& film) {
    const TileRenderer renderer(scene, tracer, options, order, film);
    tbb::enumerable_thread_specific<TileBuffers> buffers;
    ProgressReporter progress(options.progress, options.label, tiles.size());
    const auto start = std::chrono::steady_clock::now();
    // One tile per task, taken in Hilbert order.
    tbb::parallel_for(tbb::blocked_range<size_t>(0, tiles.size(), 1),
                      [&](const tbb::blocked_range<size_t>& r) {
                          for (size_t t = r.begin(); t != r.end(); ++t) {
                              renderer.render(tiles[t], buffers.local());
                              progress.tileDone();
                          }
                      },
                      tbb::simple_partitioner());
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

Image render(const SceneDescription& scene, const Tracer& tracer, const RenderOptions& options, RenderStats& stats) {
    const RenderOptions resolved = resolveRenderOptions(scene, options);
    checkRenderFits(resolved, options.label.empty() ? scene.file.string() : options.label);
    const TileOrder order(resolved.width, resolved.height, resolved.tileSize);
    Film film(resolved.width, resolved.height, resolved.aov, resolved.samplesPerPixel);
    stats.seconds = renderTiles(scene, tracer, resolved, order, order.tiles(), film);
    return film.finish(stats);
}

} // namespace wideray
