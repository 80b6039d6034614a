#include "render/tile_order.h"

#include <algorithm>

namespace wideray {

uint64_t hilbertIndex(uint32_t x, uint32_t y, int order) {
    const uint32_t n = 1u << order;
    uint64_t d = 0;
    for (uint32_t s = n / 2; s > 0; s /= 2) {
        uint32_t rx = (x & s) ? 1 : 0;
        uint32_t ry = (y & s) ? 1 : 0;
        d += uint64_t(s) * s * ((3 * rx) ^ ry);
        if (ry == 0) {  // rotate the quadrant so that the curve stays continuous
            if (rx == 1) {
                x = n - 1 - x;
                y = n - 1 - y;
            }
            std::swap(x, y);
        }
    }
    return d;
}

uint32_t mortonEncode(uint32_t x, uint32_t y) {
    auto spread = [](uint32_t v) {
        v &= 0xFFFF;
        v = (v | (v << 8)) & 0x00FF00FF;
        v = (v | (v << 4)) & 0x0F0F0F0F;
        v = (v | (v << 2)) & 0x33333333;
        v = (v | (v << 1)) & 0x55555555;
        return v;
    };
    return spread(x) | (spread(y) << 1);
}

void mortonDecode(uint32_t code, uint32_t& x, uint32_t& y) {
    auto compact = [](uint32_t v) {
        v &= 0x55555555;
        v = (v | (v >> 1)) & 0x33333333;
        v = (v | (v >> 2)) & 0x0F0F0F0F;
        v = (v | (v >> 4)) & 0x00FF00FF;
        v = (v | (v >> 8)) & 0x0000FFFF;
        return v;
    };
    x = compact(code);
    y = compact(code >> 1);
}

std::vector<TileRect> hilbertTiles(int width, int height, int tileSize) {
    int tilesX = (width + tileSize - 1) / tileSize, tilesY = (height + tileSize - 1) / tileSize;
    int order = 1;
    while ((1 << order) < std::max(tilesX, tilesY)) ++order;
    std::vector<std::pair<uint64_t, TileRect>> keyed;
    for (int ty = 0; ty < tilesY; ++ty)
        for (int tx = 0; tx < tilesX; ++tx) {
            TileRect r{tx * tileSize, ty * tileSize, std::min(width, (tx + 1) * tileSize),
                       std::min(height, (ty + 1) * tileSize)};
            keyed.push_back({hilbertIndex(uint32_t(tx), uint32_t(ty), order), r});
        }
    std::sort(keyed.begin(), keyed.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    std::vector<TileRect> tiles;
    for (const auto& k : keyed) tiles.push_back(k.second);
    return tiles;
}

std::vector<uint32_t> mortonPixelOrder(int tileSize) {
    std::vector<uint32_t> order;
    for (uint32_t code = 0; code < uint32_t(tileSize * tileSize); ++code) {
        uint32_t x, y;
        mortonDecode(code, x, y);
        order.push_back(y * uint32_t(tileSize) + x);
    }
    return order;
}

} // namespace wideray
