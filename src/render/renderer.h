#pragma once
// The renderer: the image cut into tiles (Hilbert order, render/tile_order.h), each rendered by a
// TileRenderer into one Film, the tiles run by a TileScheduler (oneTBB by default).
#include "backends/tracer.h"
#include "core/image.h"
#include "core/scene.h"
#include "render/render_options.h"
#include "render/tile_scheduler.h"

namespace wideray {

/// Renders `scene` through `tracer`, whose geometry is the scene's; `scheduler` null runs the tiles on
/// oneTBB. The color AOV is linear RGB; normal is n * 0.5 + 0.5; depth is the first hit's t (0 on a
/// miss); cost is a heatmap of nodes + primitives visited by the primary rays, scaled to the image
/// maximum.
Image render(const Scene& scene, const Tracer& tracer, const RenderOptions& options, RenderStats& stats,
             TileScheduler* scheduler = nullptr);

} // namespace wideray
