#pragma once
// The tracer interface: what the renderer and the benchmarks trace batches of rays through. A tracer
// is a cheap object over an acceleration structure (backends/structure.h) and a choice of kernels.
#include <cstdint>
#include <span>
#include <string>

#include "core/ray.h"
#include "geometry/scene_geometry.h"

namespace wideray {

class Tracer {
public:
    virtual ~Tracer() = default;

    /// Closest hits; hits[i] starts as a miss. `costs` (optional) receives per-ray traversal work.
    virtual void intersect(std::span<const Ray> rays, std::span<Hit> hits, Coherence coherence,
                           TraversalCost* costs = nullptr) const = 0;
    /// occluded[i] = 1 if anything lies within [tnear, tfar] of ray i. `depth` is the recursion depth
    /// the shadow rays start from, which a kernel may use to keep state per depth (-1: none).
    virtual void occluded(std::span<const Ray> rays, std::span<uint8_t> occluded, Coherence coherence,
                          int depth = -1) const = 0;

    /// The geometry the hits' geomIds name.
    virtual const SceneGeometry& geometry() const = 0;
    /// What the kernels' own state (such as a cache) did so far, one line per item; empty if nothing.
    virtual std::string statsReport() const { return {}; }
    virtual std::string description() const = 0;
};

} // namespace wideray
