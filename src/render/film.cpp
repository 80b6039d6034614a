#include "render/film.h"

#include <algorithm>
#include <stdexcept>

#include "render/heatmap.h"

namespace wideray {

Film::Film(int width, int height, Aov aov, int samplesPerPixel)
    : aov_(aov), sampleWeight_(1.0f / float(samplesPerPixel)), image_(width, height, aov == Aov::Depth ? 1 : 3),
      cost_(aov == Aov::Cost ? size_t(width) * size_t(height) : 0) {}

namespace {

size_t pixelCount(std::span<const TileRect> tiles) {
    size_t n = 0;
    for (const TileRect& t : tiles) n += size_t(t.x1 - t.x0) * size_t(t.y1 - t.y0);
    return n;
}

/// Calls fn(offset in the image's pixels, offset in the part's) for each row of each tile, with the
/// row's length in pixels.
template <class Fn>
void forEachTileRow(std::span<const TileRect> tiles, int width, Fn fn) {
    size_t partOffset = 0;
    for (const TileRect& t : tiles)
        for (int y = t.y0; y < t.y1; ++y) {
            const size_t length = size_t(t.x1 - t.x0);
            fn(size_t(y) * size_t(width) + size_t(t.x0), partOffset, length);
            partOffset += length;
        }
}

} // namespace

FilmTiles Film::extract(std::span<const TileRect> tiles) const {
    const size_t channels = size_t(image_.channels);
    FilmTiles part;
    part.pixels.resize(pixelCount(tiles) * channels);
    if (aov_ == Aov::Cost) part.cost.resize(pixelCount(tiles));
    forEachTileRow(tiles, image_.width, [&](size_t image, size_t offset, size_t length) {
        std::copy_n(image_.pixels.begin() + ptrdiff_t(image * channels), length * channels,
                    part.pixels.begin() + ptrdiff_t(offset * channels));
        if (aov_ == Aov::Cost) std::copy_n(cost_.begin() + ptrdiff_t(image), length, part.cost.begin() + ptrdiff_t(offset));
    });
    part.primaryRays = primaryRays_;
    part.secondaryRays = secondaryRays_;
    part.shadowRays = shadowRays_;
    return part;
}

void Film::insert(std::span<const TileRect> tiles, const FilmTiles& part) {
    const size_t channels = size_t(image_.channels), pixels = pixelCount(tiles);
    if (part.pixels.size() != pixels * channels || part.cost.size() != (aov_ == Aov::Cost ? pixels : 0))
        throw std::invalid_argument("Film::insert: the part's size does not match its tiles");
    forEachTileRow(tiles, image_.width, [&](size_t image, size_t offset, size_t length) {
        std::copy_n(part.pixels.begin() + ptrdiff_t(offset * channels), length * channels,
                    image_.pixels.begin() + ptrdiff_t(image * channels));
        if (aov_ == Aov::Cost) std::copy_n(part.cost.begin() + ptrdiff_t(offset), length, cost_.begin() + ptrdiff_t(image));
    });
    primaryRays_ += part.primaryRays;
    secondaryRays_ += part.secondaryRays;
    shadowRays_ += part.shadowRays;
}

Image Film::finish(RenderStats& stats) {
    stats.primaryRays = primaryRays_;
    stats.secondaryRays = secondaryRays_;
    stats.shadowRays = shadowRays_;
    if (aov_ == Aov::Cost) {
        uint32_t maxCost = 1;
        for (uint32_t c : cost_) maxCost = std::max(maxCost, c);
        stats.maxCost = maxCost;
        for (size_t p = 0; p < cost_.size(); ++p) {
            glm::vec3 c = heatmapColor(float(cost_[p]) / float(maxCost));
            for (int k = 0; k < 3; ++k) image_.pixels[p * 3 + k] = c[k];
        }
    }
    return std::move(image_);
}

} // namespace wideray
