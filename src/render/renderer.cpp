#include "render/renderer.h"

#include <chrono>

#include <tbb/enumerable_thread_specific.h>

#include "render/film.h"
#include "render/progress.h"
#include "render/tile_renderer.h"

namespace wideray {

Image render(const Scene& scene, const Tracer& tracer, const RenderOptions& options, RenderStats& stats,
             TileScheduler* scheduler) {
    RenderOptions resolved = options;
    resolved.width = options.width > 0 ? options.width : scene.image.width;
    resolved.height = options.height > 0 ? options.height : scene.image.height;
    resolved.samplesPerPixel = options.samplesPerPixel > 0 ? options.samplesPerPixel : scene.image.samplesPerPixel;
    if (resolved.tileSize == 0) resolved.tileSize = renderTileSize(scene, resolved.samplesPerPixel);

    const TileOrder order(resolved.width, resolved.height, resolved.tileSize);
    Film film(resolved.width, resolved.height, resolved.aov, resolved.samplesPerPixel);
    const TileRenderer renderer(scene, tracer, resolved, order, film);
    tbb::enumerable_thread_specific<TileBuffers> buffers;
    ProgressReporter progress(options.progress, options.label, order.tiles().size());
    TbbTileScheduler tbbScheduler;

    const auto start = std::chrono::steady_clock::now();
    (scheduler ? *scheduler : tbbScheduler).run(order.tiles(), [&](const TileRect& tile) {
        renderer.render(tile, buffers.local());
        progress.tileDone();
    });
    stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return film.finish(stats);
}

} // namespace wideray
