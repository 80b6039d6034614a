#pragma once
// The ray sets of `wideray bench` (see docs/performance.md), reproducible from a scene alone:
// primary rays through pixel centers (16x16 tiles in Hilbert order, Morton order inside each),
// shadow rays from each primary hit toward the first point light (tnear = 1e-3 R, tfar = the
// light's distance), diffuse rays from each primary hit in a cosine-weighted direction about
// the geometric normal turned toward the camera (tnear = 1e-3 R, seeded by the pixel), and bounce
// rays: the rays of bounces 2 to 4 of the path tracer at one sample per pixel, tile after tile, as
// the renderer traces them.
#include <string_view>
#include <vector>

#include "core/ray.h"
#include "core/scene.h"
#include "backends/tracer.h"

namespace wideray {

enum class RayKind { Primary, Shadow, Diffuse, Bounce };

struct RayKindInfo {
    RayKind kind;
    const char* name;
    bool anyHit;    ///< occlusion queries rather than closest hits
    bool coherent;  ///< traced as the renderer traces coherent batches
};

/// Every ray kind, in the order bench measures them.
const std::vector<RayKindInfo>& rayKinds();
/// The kind named `name`, or null.
const RayKindInfo* findRayKind(std::string_view name);
const char* rayKindName(RayKind kind);

struct BenchRays {
    std::vector<Ray> primary, shadow, diffuse, bounce;
    float sceneRadius = 1.0f;  ///< R: half the diagonal of the scene bounds

    const std::vector<Ray>& of(RayKind kind) const {
        switch (kind) {
        case RayKind::Primary: return primary;
        case RayKind::Shadow: return shadow;
        case RayKind::Diffuse: return diffuse;
        case RayKind::Bounce: break;
        }
        return bounce;
    }
};

/// Primary hits come from `reference`, whose hits define the secondary rays and whose paths the bounce rays follow.
BenchRays makeBenchRays(const SceneDescription& scene, const Tracer& reference, int width, int height);

/// Camera rays of a width x height image in the renderer's order (tiles in Hilbert order, pixels in
/// Morton order inside a tile), through pixel centers.
std::vector<Ray> primaryRays(const SceneDescription& scene, int width, int height);

} // namespace wideray
