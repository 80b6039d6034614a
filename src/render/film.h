#pragma once
// What a render produces: the image of its AOV (linear color; n * 0.5 + 0.5; the first hit's t), the
// per-pixel traversal cost behind the cost heatmap, and the ray counts. Tiles write disjoint pixels,
// so threads share a film without locks; the counts are atomic.
#include <atomic>
#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "core/image.h"
#include "render/render_options.h"
#include "render/tile_order.h"

namespace wideray {

/// What a film holds for some of its tiles: their pixels (all channels) and, for the cost AOV, their
/// per-pixel costs, tile after tile and row by row inside each tile, with the rays the film counted.
/// The share of an image that one MPI rank renders and sends to the rank that writes the image.
struct FilmTiles {
    std::vector<float> pixels;
    std::vector<uint32_t> cost;
    uint64_t primaryRays = 0, secondaryRays = 0, shadowRays = 0;
};

class Film {
public:
    Film(int width, int height, Aov aov, int samplesPerPixel);

    Aov aov() const { return aov_; }
    int width() const { return image_.width; }
    int height() const { return image_.height; }

    /// Adds one sample's share of `color` to the pixel (color and normal AOVs).
    void addSample(uint32_t x, uint32_t y, const glm::vec3& color) {
        float* out = image_.at(int(x), int(y));
        for (int c = 0; c < 3; ++c) out[c] += color[c] * sampleWeight_;
    }
    /// Adds one sample's share of a depth (depth AOV).
    void addDepth(uint32_t x, uint32_t y, float depth) { image_.at(int(x), int(y))[0] += depth * sampleWeight_; }
    /// Adds nodes + primitives visited by a camera ray (cost AOV).
    void addCost(uint32_t x, uint32_t y, uint32_t cost) { cost_[size_t(y) * size_t(image_.width) + x] += cost; }

    void countPrimaryRays(uint64_t n) { primaryRays_ += n; }
    void countSecondaryRays(uint64_t n) { secondaryRays_ += n; }
    void countShadowRays(uint64_t n) { shadowRays_ += n; }

    /// The values of `tiles`, and every ray this film counted.
    FilmTiles extract(std::span<const TileRect> tiles) const;
    /// Sets the values of `tiles` from `part` (as extract gave them) and adds its rays. Throws
    /// std::invalid_argument when the part's sizes do not fit the tiles.
    void insert(std::span<const TileRect> tiles, const FilmTiles& part);

    /// The finished image (cost: a heatmap scaled to the largest pixel cost); the counts go to `stats`.
    Image finish(RenderStats& stats);

private:
    Aov aov_;
    float sampleWeight_;
    Image image_;
    std::vector<uint32_t> cost_;
    std::atomic<uint64_t> primaryRays_{0}, secondaryRays_{0}, shadowRays_{0};
};

} // namespace wideray
