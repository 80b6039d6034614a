#pragma once
// The last-occluder cache of shadow rays (Haines and Greenberg 1986, "The Light Buffer"; the "shadow
// cache" of the ray tracing course material).
#include <cstdint>

namespace wideray {

/// One thread's cache for the shadow rays of one recursion depth: the leaf block (of 4 triangles)
/// that last blocked one of its rays is tested first, before any traversal.
struct alignas(64) ShadowCache {  // a cache line each: threads update their own
    uint32_t block = UINT32_MAX;
    uint64_t queries = 0, hits = 0;
};

} // namespace wideray
