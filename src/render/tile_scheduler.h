#pragma once
// Who renders which tile, and when. The renderer hands a scheduler the image's tiles in Hilbert order
// and a function that renders one; today's scheduler runs them on the oneTBB workers of this process.
// An MPI scheduler would run its rank's share and gather the films (docs/architecture.md).
#include <functional>
#include <span>

#include "render/tile_order.h"

namespace wideray {

class TileScheduler {
public:
    virtual ~TileScheduler() = default;
    /// Calls renderTile once for each tile (from any thread) and returns when all are done.
    virtual void run(std::span<const TileRect> tiles, const std::function<void(const TileRect&)>& renderTile) = 0;
};

/// The tiles on oneTBB's worker threads, one tile per task, taken in their order.
class TbbTileScheduler final : public TileScheduler {
public:
    void run(std::span<const TileRect> tiles, const std::function<void(const TileRect&)>& renderTile) override;
};

} // namespace wideray
