#pragma once
// The accelerator interface: what the renderer and the benchmarks trace batches of rays through.
// Implemented by our kernels over the wide BVH and by the Embree backend; kd-trees and grids fit here.
#include <cstdint>
#include <span>
#include <string>
#include <utility>

#include "core/geometry.h"
#include "core/ray.h"

namespace wideray {

/// How a batch of rays was made: coherent batches come in screen-space blocks (Morton order) and
/// go to packet kernels; incoherent ones go to the kernel chosen for them.
enum class Coherence { Coherent, Incoherent };

class Tracer {
public:
    virtual ~Tracer() = default;

    /// Closest hits; hits[i] starts as a miss. `costs` (optional) receives per-ray traversal work.
    virtual void intersect(std::span<const Ray> rays, std::span<Hit> hits, Coherence coherence,
                           TraversalCost* costs = nullptr) const = 0;
    /// occluded[i] = 1 if anything lies within [tnear, tfar] of ray i. `depth` is the recursion depth
    /// the shadow rays start from, which picks the shadow cache a tracer may keep (-1: none).
    virtual void occluded(std::span<const Ray> rays, std::span<uint8_t> occluded, Coherence coherence,
                          int depth = -1) const = 0;

    /// The geometry a hit's geomId names (geomId 0, the triangles, is resolved by the caller).
    virtual const Geometry& geometry(uint32_t geomId) const = 0;
    /// Shadow-cache queries and hits so far; zeros for a tracer without one.
    virtual std::pair<uint64_t, uint64_t> shadowCacheStats() const { return {0, 0}; }
    virtual std::string description() const = 0;
};

} // namespace wideray
