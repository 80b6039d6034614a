#pragma once
// Deterministic random numbers: seeded from pixel, sample and purpose, never from the thread or the
// schedule, so images do not change with the thread count or the tile order.
#include <cstdint>

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

} // namespace wideray
