#pragma once
// The last-occluder cache of shadow rays (Haines and Greenberg 1986, "The Light Buffer"; the "shadow
// cache" of the ray tracing course material).
#include <cstdint>

namespace wideray {

/// One thread's cache for the shadow rays of one recursion depth: the leaf blocks (of 4 triangles)
/// that last blocked its rays, most recent first, are tested before any traversal.
struct alignas(64) ShadowCache {  // a cache line each: threads update their own
    static constexpr int kBlocks = 2;  // measured against 1 and 4: docs/performance-analysis.md
    static constexpr uint32_t kEmpty = UINT32_MAX;
    uint32_t blocks[kBlocks] = {kEmpty, kEmpty};
    uint32_t found = kEmpty;  ///< where a traversal writes the block that occluded one of its rays
    uint64_t queries = 0, hits = 0;

    /// Puts the block a traversal found first, if it found one.
    void remember() {
        if (found == kEmpty) return;
        int e = 0;
        while (e < kBlocks - 1 && blocks[e] != found) ++e;
        for (; e > 0; --e) blocks[e] = blocks[e - 1];
        blocks[0] = found;
        found = kEmpty;
    }

    /// Moves entry e first (it answered a ray).
    void promote(int e) {
        const uint32_t block = blocks[e];
        for (; e > 0; --e) blocks[e] = blocks[e - 1];
        blocks[0] = block;
    }

    /// Drops entry e (it answered none of a packet's rays).
    void forget(int e) {
        for (; e < kBlocks - 1; ++e) blocks[e] = blocks[e + 1];
        blocks[kBlocks - 1] = kEmpty;
    }
};

} // namespace wideray
