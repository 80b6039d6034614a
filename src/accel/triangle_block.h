#pragma once
// M triangles of a BVH leaf stored as structure of arrays, so that one ray tests all M at once.
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

    int count() const {
        int n = 0;
        while (n < M && primId[n] != kInvalidId) ++n;
        return n;
    }
};
static_assert(sizeof(TriangleBlock<4>) == 160);

/// The leaf blocks of a BVH, sized before the collapse writes them in parallel.
using TriangleBlocks = UninitializedVector<TriangleBlock<kBlockSize>>;

} // namespace wideray
