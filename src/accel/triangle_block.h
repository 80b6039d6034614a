#pragma once
// M triangles of a BVH leaf stored as structure of arrays, so that one ray tests all M at once.
#include <cstddef>
#include <cstdint>

#include "core/default_init_allocator.h"
#include "core/ray.h"

namespace wideray {

/// Triangles per leaf block (the M of the kernels).
constexpr int kBlockSize = 4;

template <int M>
struct alignas(16) TriangleBlock {
    float v0x[M], v0y[M], v0z[M];
    float v1x[M], v1y[M], v1z[M];
    float v2x[M], v2y[M], v2z[M];
    uint32_t primId[M];  ///< kInvalidId in unused lanes

    /// The nine coordinate arrays in one: coordinates()[(3 * vertex + axis) * M + lane].
    const float* coordinates() const { return v0x; }

    int count() const {
        int n = 0;
        while (n < M && primId[n] != kInvalidId) ++n;
        return n;
    }
};
static_assert(sizeof(TriangleBlock<4>) == 160);
static_assert(offsetof(TriangleBlock<4>, v2z) == 8 * 4 * sizeof(float), "coordinate arrays are contiguous");

/// The leaf blocks of a BVH, sized before the collapse writes them in parallel.
using TriangleBlocks = UninitializedVector<TriangleBlock<kBlockSize>>;

} // namespace wideray
