#pragma once
// A traversal kernel as a pair of function pointers, chosen once per tracer (never per ray).
#include <cstddef>
#include <cstdint>

#include "accel/bvh_view.h"
#include "core/ray.h"

namespace wideray {

/// The last-occluder cache of one thread for shadow rays of one recursion depth: the leaf block
/// (of 4 triangles) that blocked the previous shadow ray is tested first (Haines and Greenberg 1986,
/// "The Light Buffer"; the "shadow cache" of the ray tracing course material).
struct alignas(64) ShadowCache {  // a cache line each: threads update their own
    uint32_t block = UINT32_MAX;
    uint64_t queries = 0, hits = 0;
};

template <int N>
struct KernelSet {
    using IntersectFn = void (*)(const SceneView<N>&, const Ray*, Hit*, size_t, TraversalCost*);
    using OccludedFn = void (*)(const SceneView<N>&, const Ray*, uint8_t*, size_t);
    const char* name = "";
    IntersectFn intersect = nullptr;
    OccludedFn occluded = nullptr;
    /// Occlusion with a shadow cache; only the single-ray kernel has it.
    using OccludedCachedFn = void (*)(const SceneView<N>&, const Ray*, uint8_t*, size_t, ShadowCache&);
    OccludedCachedFn occludedCached = nullptr;
};

} // namespace wideray
