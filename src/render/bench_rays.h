#pragma once
// The ray sets of `wideray bench` (see docs/performance.md), reproducible from a scene alone:
// primary rays through pixel centers (16x16 tiles in Hilbert order, Morton order inside each),
// shadow rays from each primary hit toward the first point light (tnear = 1e-3 R, tfar = the
// light's distance), and diffuse rays from each primary hit in a cosine-weighted direction about
// the geometric normal turned toward the camera (tnear = 1e-3 R, seeded by the pixel).
#include <vector>

#include "core/ray.h"
#include "core/scene.h"
#include "backends/tracer.h"

namespace wideray {

enum class RayKind { Primary, Shadow, Diffuse };
const char* rayKindName(RayKind kind);

struct BenchRays {
    std::vector<Ray> primary, shadow, diffuse;
    float sceneRadius = 1.0f;  ///< R: half the diagonal of the scene bounds

    const std::vector<Ray>& of(RayKind kind) const {
        return kind == RayKind::Primary ? primary : kind == RayKind::Shadow ? shadow : diffuse;
    }
};

/// Primary hits come from `reference`, whose hits define the secondary rays.
BenchRays makeBenchRays(const Scene& scene, const Tracer& reference, int width, int height);

/// Camera rays of a width x height image in the renderer's order (tiles in Hilbert order, pixels in
/// Morton order inside a tile), through pixel centers.
std::vector<Ray> primaryRays(const Scene& scene, int width, int height);

} // namespace wideray
