#pragma once
// Deterministic random numbers: seeded from pixel, sample and purpose, never from the thread or the
// schedule, so images do not change with the thread count or the tile order.
#include <cmath>
#include <cstdint>

#include <glm/glm.hpp>

namespace wideray {

/// PCG-style integer hash (Jarzynski and Olano 2020, "Hash Functions for GPU Rendering").
inline uint32_t pcgHash(uint32_t v) {
    uint32_t state = v * 747796405u + 2891336453u;
    uint32_t word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return (word >> 22u) ^ word;
}

class SampleRng {
public:
    SampleRng(uint32_t x, uint32_t y, uint32_t sample, uint32_t purpose = 0)
        : state_(pcgHash(x ^ pcgHash(y ^ pcgHash(sample ^ pcgHash(purpose))))) {}

    uint32_t nextUint() {
        state_ = pcgHash(state_);
        return state_;
    }
    /// Uniform in [0, 1).
    float next() { return float(nextUint() >> 8) * (1.0f / 16777216.0f); }

private:
    uint32_t state_;
};

/// A jittered point in cell `index` of a grid of `count` cells over [0, 1)^2. The grid has as many
/// columns as the largest divisor of `count` not above its square root, so that every count tiles the
/// square exactly and the points stay unbiased (4: 2x2, 8: 2x4, 7: 1x7).
inline glm::vec2 stratifiedPoint(int index, int count, SampleRng& rng) {
    int columns = int(std::sqrt(float(count)));
    while (count % columns != 0) --columns;
    const int rows = count / columns;
    const float u = (float(index % columns) + rng.next()) / float(columns);
    const float v = (float(index / columns) + rng.next()) / float(rows);
    return {u, v};
}

} // namespace wideray
