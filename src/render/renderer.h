#pragma once
// The renderer: the image cut into tiles (Hilbert order, render/tile_order.h), each rendered by a
// TileRenderer into one Film, the tiles run on oneTBB's threads. A distributed render (src/mpi/)
// renders runs of the same tiles on several processes and joins their films (render/frame_parts.h).
#include <span>

#include "backends/tracer.h"
#include "core/image.h"
#include "core/scene.h"
#include "render/film.h"
#include "render/render_options.h"
#include "render/tile_order.h"

namespace wideray {

/// `options` with what it leaves at 0 taken from the scene: image size and samples per pixel, and
/// the tile size chosen (renderTileSize).
RenderOptions resolveRenderOptions(const SceneDescription& scene, const RenderOptions& options);

/// Renders `tiles` (a subset of `order`'s) into `film` on oneTBB's threads; `options` resolved.
/// Returns the seconds it took.
double renderTiles(const SceneDescription& scene, const Tracer& tracer, const RenderOptions& options, const TileOrder& order,
                   std::span<const TileRect> tiles, Film& film);

/// Renders `scene` through `tracer`, whose geometry is the scene's. The color AOV is linear RGB;
/// normal is n * 0.5 + 0.5; depth is the first hit's t (0 on a miss); cost is a heatmap of nodes +
/// primitives visited by the primary rays, scaled to the image maximum.
Image render(const SceneDescription& scene, const Tracer& tracer, const RenderOptions& options, RenderStats& stats);

} // namespace wideray
