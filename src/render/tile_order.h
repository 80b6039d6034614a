#pragma once
// Orders of work on the image: tiles along a Hilbert curve (neighbouring tiles run close in time, so
// they share cached BVH nodes), pixels inside a tile in Morton (Z) order (so that consecutive groups
// of 4, 8 and 16 rays are 2x2, 4x2 and 4x4 pixel blocks).
#include <cstdint>
#include <vector>

namespace wideray {

struct TileRect {
    int x0, y0, x1, y1;  ///< pixels [x0, x1) x [y0, y1)
};

/// Index of cell (x, y) along the Hilbert curve over a 2^order x 2^order grid.
uint64_t hilbertIndex(uint32_t x, uint32_t y, int order);

/// Interleaves the bits of x and y (x in the even bits).
uint32_t mortonEncode(uint32_t x, uint32_t y);
void mortonDecode(uint32_t code, uint32_t& x, uint32_t& y);

/// The image's tiles of tileSize x tileSize pixels, in Hilbert-curve order.
std::vector<TileRect> hilbertTiles(int width, int height, int tileSize);

/// Pixel offsets (x, y packed as y * tileSize + x) of a tileSize x tileSize tile in Morton order;
/// tileSize is a power of two.
std::vector<uint32_t> mortonPixelOrder(int tileSize);

/// The renderer's order of work on an image, which the benchmarks' ray sets reproduce: tiles along a
/// Hilbert curve, the pixels of each tile in Morton order.
class TileOrder {
public:
    TileOrder(int width, int height, int tileSize)
        : tileSize_(tileSize), tiles_(hilbertTiles(width, height, tileSize)), morton_(mortonPixelOrder(tileSize)) {}

    const std::vector<TileRect>& tiles() const { return tiles_; }

    /// Calls fn(x, y) for the pixels of `tile` in Morton order.
    template <class Fn>
    void forEachPixel(const TileRect& tile, Fn fn) const {
        for (uint32_t local : morton_) {
            const int x = tile.x0 + int(local % uint32_t(tileSize_)), y = tile.y0 + int(local / uint32_t(tileSize_));
            if (x < tile.x1 && y < tile.y1) fn(x, y);
        }
    }
    /// Calls fn(x, y) for every pixel of the image, tile after tile.
    template <class Fn>
    void forEachPixel(Fn fn) const {
        for (const TileRect& tile : tiles_) forEachPixel(tile, fn);
    }

private:
    int tileSize_;
    std::vector<TileRect> tiles_;
    std::vector<uint32_t> morton_;
};

} // namespace wideray
