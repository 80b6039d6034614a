#include "render/bench_rays.h"

#include <cmath>

#include <tbb/parallel_for.h>

#include "core/bounds.h"
#include "render/camera.h"
#include "core/random.h"
#include "render/tile_order.h"

namespace wideray {
namespace {

constexpr int kTileSize = 16;

Ray rayFrom(const glm::vec3& o, const glm::vec3& d, float tnear, float tfar) {
    return {o.x, o.y, o.z, d.x, d.y, d.z, tnear, tfar};
}

/// Cosine-weighted direction about n (Malley's method through a concentric-free polar map).
glm::vec3 cosineDirection(const glm::vec3& n, float u1, float u2) {
    float r = std::sqrt(u1), phi = 2.0f * float(M_PI) * u2;
    glm::vec3 t = std::fabs(n.x) > 0.5f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
    glm::vec3 b1 = glm::normalize(glm::cross(n, t)), b2 = glm::cross(n, b1);
    return glm::normalize(r * std::cos(phi) * b1 + r * std::sin(phi) * b2 + std::sqrt(std::max(0.0f, 1.0f - u1)) * n);
}

} // namespace

const char* rayKindName(RayKind kind) {
    switch (kind) {
    case RayKind::Primary: return "primary";
    case RayKind::Shadow: return "shadow";
    case RayKind::Diffuse: return "diffuse";
    }
    return "?";
}

std::vector<Ray> primaryRays(const Scene& scene, int width, int height) {
    CameraModel camera(scene.camera, width, height);
    std::vector<Ray> rays;
    rays.reserve(size_t(width) * height);
    TileOrder(width, height, kTileSize).forEachPixel([&](int x, int y) {
        rays.push_back(camera.generate(float(x) + 0.5f, float(y) + 0.5f));
    });
    return rays;
}

BenchRays makeBenchRays(const Scene& scene, const Tracer& reference, int width, int height) {
    BenchRays out;
    const Bounds3f bounds = reference.geometry().bounds();
    out.sceneRadius = bounds.empty() ? 1.0f : 0.5f * glm::length(bounds.extent());
    const float tnear = 1e-3f * out.sceneRadius;

    out.primary = primaryRays(scene, width, height);
    std::vector<Hit> hits(out.primary.size());
    tbb::parallel_for(tbb::blocked_range<size_t>(0, out.primary.size(), 4096), [&](const tbb::blocked_range<size_t>& r) {
        reference.intersect(std::span(out.primary).subspan(r.begin(), r.size()), std::span(hits).subspan(r.begin(), r.size()),
                            Coherence::Coherent);
    });

    glm::vec3 light = scene.camera.position;
    for (const Light& l : scene.lights)
        if (l.type == LightType::Point) {
            light = l.position;
            break;
        }
    // Pixel coordinates of each primary ray, for the per-pixel seed.
    std::vector<uint32_t> pixelOf;
    TileOrder(width, height, kTileSize).forEachPixel([&](int x, int y) {
        pixelOf.push_back(uint32_t(y) * uint32_t(width) + uint32_t(x));
    });
    for (size_t i = 0; i < hits.size(); ++i) {
        if (!hits[i].valid()) continue;
        const Ray& ray = out.primary[i];
        SurfacePoint sp = reference.geometry().surface(ray, hits[i]);
        glm::vec3 dir(ray.dx, ray.dy, ray.dz);
        glm::vec3 toLight = light - sp.position;
        float dist = glm::length(toLight);
        if (dist > tnear) out.shadow.push_back(rayFrom(sp.position, toLight / dist, tnear, dist));
        glm::vec3 n = glm::dot(sp.geometricNormal, dir) < 0.0f ? sp.geometricNormal : -sp.geometricNormal;
        SampleRng rng(pixelOf[i] % uint32_t(width), pixelOf[i] / uint32_t(width), 0, 7);
        float u1 = rng.next(), u2 = rng.next();
        out.diffuse.push_back(rayFrom(sp.position, cosineDirection(n, u1, u2), tnear, INFINITY));
    }
    return out;
}

} // namespace wideray
