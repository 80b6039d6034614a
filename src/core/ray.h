#pragma once
// A single ray and its closest hit, the currency of every tracer.
#include <cstdint>
#include <limits>

namespace wideray {

constexpr uint32_t kInvalidId = UINT32_MAX;

/// A ray with a parametric interval [tnear, tfar]. Rays with a NaN or infinite component, a zero
/// direction or tnear > tfar are invalid: every kernel reports them as a miss and not occluded.
struct Ray {
    float ox = 0, oy = 0, oz = 0;
    float dx = 0, dy = 0, dz = 1;
    float tnear = 0;
    float tfar = std::numeric_limits<float>::infinity();
    float time = 0;  ///< within the camera's shutter, in [0, 1]: where moving objects are (motion blur)
};

/// The closest hit along a ray. geomId 0 is the scene's triangles; user geometries follow.
/// u and v weight the second and third triangle vertex. Equal t is resolved by the smaller
/// (geomId, primId), so every kernel finds the same hit whatever its traversal order.
struct Hit {
    float t = std::numeric_limits<float>::infinity();
    float u = 0, v = 0;
    uint32_t primId = kInvalidId;
    uint32_t geomId = kInvalidId;

    bool valid() const { return primId != kInvalidId; }
};

/// Traversal work for one ray: the cost AOV and the kernel statistics.
struct TraversalCost {
    uint32_t nodes = 0;       ///< inner nodes whose children were tested
    uint32_t leaves = 0;      ///< leaves entered
    uint32_t primitives = 0;  ///< primitive tests (a triangle block counts its kBlockSize slots)
    uint32_t mailboxHits = 0; ///< kd-tree and grids: tests skipped, the ray having tested the primitive before
};

} // namespace wideray
