#include "render/bench_rays.h"

#include <cmath>

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include "core/bounds.h"
#include "core/random.h"
#include "render/camera.h"
#include "render/film.h"
#include "render/tile_order.h"
#include "render/tile_renderer.h"
#include "shading/material_model.h"

namespace wideray {
namespace {

constexpr int kTileSize = 16;

Ray rayFrom(const glm::vec3& o, const glm::vec3& d, float tnear, float tfar, float time) {
    return {o.x, o.y, o.z, d.x, d.y, d.z, tnear, tfar, time};
}

constexpr int kFirstBounce = 2, kLastBounce = 4;

/// The rays of bounces kFirstBounce..kLastBounce of the path tracer at one sample per pixel, tile
/// after tile in the renderer's order.
std::vector<Ray> bounceRays(const SceneDescription& scene, const Tracer& tracer, int width, int height) {
    SceneDescription pathTraced = scene;
    pathTraced.render.integrator = Integrator::Path;
    RenderOptions options;
    options.width = width;
    options.height = height;
    options.samplesPerPixel = 1;
    options.tileSize = renderTileSize(pathTraced, 1);
    const TileOrder order(width, height, options.tileSize);
    Film film(width, height, Aov::Color, 1);
    const TileRenderer renderer(pathTraced, tracer, options, order, film);
    tbb::enumerable_thread_specific<TileBuffers> buffers;
    std::vector<std::vector<Ray>> perTile(order.tiles().size());
    tbb::parallel_for(size_t(0), perTile.size(), [&](size_t t) {
        TileBuffers& buf = buffers.local();
        buf.firstRecorded = kFirstBounce;
        buf.lastRecorded = kLastBounce;
        buf.recorded.clear();
        renderer.render(order.tiles()[t], buf);
        perTile[t] = std::move(buf.recorded);
    });
    std::vector<Ray> rays;
    for (const std::vector<Ray>& tile : perTile) rays.insert(rays.end(), tile.begin(), tile.end());
    return rays;
}

} // namespace

const std::vector<RayKindInfo>& rayKinds() {
    static const std::vector<RayKindInfo> kinds = {{RayKind::Primary, "primary", false, true},
                                                   {RayKind::Shadow, "shadow", true, true},
                                                   {RayKind::Diffuse, "diffuse", false, false},
                                                   {RayKind::Bounce, "bounce", false, false}};
    return kinds;
}

const RayKindInfo* findRayKind(std::string_view name) {
    for (const RayKindInfo& k : rayKinds())
        if (name == k.name) return &k;
    return nullptr;
}

const char* rayKindName(RayKind kind) {
    for (const RayKindInfo& k : rayKinds())
        if (k.kind == kind) return k.name;
    return "?";
}

std::vector<Ray> primaryRays(const SceneDescription& scene, int width, int height) {
    CameraModel camera(scene.camera, width, height);
    std::vector<Ray> rays;
    rays.reserve(size_t(width) * height);
    TileOrder(width, height, kTileSize).forEachPixel([&](int x, int y) {
        rays.push_back(camera.generate(float(x) + 0.5f, float(y) + 0.5f));
    });
    return rays;
}

BenchRays makeBenchRays(const SceneDescription& scene, const Tracer& reference, int width, int height) {
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
        if (dist > tnear) out.shadow.push_back(rayFrom(sp.position, toLight / dist, tnear, dist, ray.time));
        glm::vec3 n = glm::dot(sp.geometricNormal, dir) < 0.0f ? sp.geometricNormal : -sp.geometricNormal;
        SampleRng rng(pixelOf[i] % uint32_t(width), pixelOf[i] / uint32_t(width), 0, 7);
        float u1 = rng.next(), u2 = rng.next();
        out.diffuse.push_back(rayFrom(sp.position, cosineDirection(n, u1, u2), tnear, INFINITY, ray.time));
    }
    out.bounce = bounceRays(scene, reference, width, height);
    return out;
}

} // namespace wideray
