#include "render/tile_scheduler.h"

#include <tbb/parallel_for.h>

namespace wideray {

void TbbTileScheduler::run(std::span<const TileRect> tiles, const std::function<void(const TileRect&)>& renderTile) {
    tbb::parallel_for(tbb::blocked_range<size_t>(0, tiles.size(), 1),
                      [&](const tbb::blocked_range<size_t>& r) {
                          for (size_t t = r.begin(); t != r.end(); ++t) renderTile(tiles[t]);
                      },
                      tbb::simple_partitioner());
}

} // namespace wideray
