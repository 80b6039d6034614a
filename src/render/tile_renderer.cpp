#include "render/tile_renderer.h"

#include <algorithm>
#include <cmath>

#include "core/random.h"
#include "shading/beer.h"
#include "shading/environment.h"
#include "shading/path_vertex.h"

namespace wideray {
namespace {

uint32_t directionOctant(const Ray& r) {
    return (r.dx < 0.0f ? 1u : 0u) | (r.dy < 0.0f ? 2u : 0u) | (r.dz < 0.0f ? 4u : 0u);
}

/// The box around the scene's objects and its lights' positions.
Bounds3f boundsWithLights(const Bounds3f& objects, const SceneDescription& scene) {
    Bounds3f b = objects;
    for (const Light& light : scene.lights) {
        if (light.type == LightType::Directional) continue;
        b.grow(light.position - glm::vec3(light.radius));
        b.grow(light.position + glm::vec3(light.radius));
        if (light.isPlanar()) {
            b.grow(light.position + light.edgeU);
            b.grow(light.position + light.edgeV);
        }
        if (light.type == LightType::Quad) b.grow(light.position + light.edgeU + light.edgeV);
    }
    return b;
}

constexpr uint32_t kCameraPurpose = 1;
/// Purposes from here on seed the random numbers of a path's bounces, one per depth.
constexpr uint32_t kBouncePurpose = 2;

/// The fraction of light left after a segment inside the medium of `material`; a segment that
/// never ends (an open mesh) keeps only the channels the medium does not absorb.
glm::vec3 mediumTransmittance(const Material& material, float distance) {
    if (std::isinf(distance)) return glm::vec3(glm::equal(material.absorption, glm::vec3(0.0f)));
    return beerTransmittance(material.absorption, distance);
}

} // namespace

int renderTileSize(const SceneDescription& scene, int samplesPerPixel) {
    if (scene.render.integrator != Integrator::Path) return 16;
    int size = 16;
    while (size < 64 && size * size * samplesPerPixel < 4096) size *= 2;
    return size;
}

TileRenderer::TileRenderer(const SceneDescription& scene, const Tracer& tracer, const RenderOptions& options,
                           const TileOrder& order, Film& film)
    : scene_(scene), tracer_(tracer), geometry_(tracer.geometry()), options_(options), order_(order), film_(film),
      camera_(scene.camera, options.width, options.height), objects_(geometry_.bounds()),
      epsilon_(1e-4f * (objects_.empty() ? 1.0f : glm::length(objects_.extent()))),
      fog_(scene.fog, boundsWithLights(objects_, scene)), shading_{scene, fog_, epsilon_},
      pathTracing_(scene.render.integrator == Integrator::Path) {}

// Primary paths of the tile in Morton order, each pixel's samples stratified over the pixel and, in a
// rotated order, over the lens.
void TileRenderer::startPaths(const TileRect& tile, std::vector<PathState>& paths) const {
    const int spp = options_.samplesPerPixel;
    paths.clear();
    order_.forEachPixel(tile, [&](int x, int y) {
        const uint32_t lensRotation = pcgHash(uint32_t(y) * uint32_t(options_.width) + uint32_t(x));
        for (int s = 0; s < spp; ++s) {
            SampleRng rng(uint32_t(x), uint32_t(y), uint32_t(s), kCameraPurpose);
            const glm::vec2 jitter = spp > 1 ? stratifiedPoint(s, spp, rng) : glm::vec2(0.5f);
            const glm::vec2 lens = stratifiedPoint(int((uint32_t(s) + lensRotation) % uint32_t(spp)), spp, rng);
            // Times stratified over the pixel's samples too, in an order of their own.
            const float shutter = (float((uint32_t(s) + pcgHash(lensRotation)) % uint32_t(spp)) + rng.next()) / float(spp);
            PathState path;
            path.ray = camera_.generate(float(x) + jitter.x, float(y) + jitter.y, lens, shutter);
            path.pixelX = uint32_t(x);
            path.pixelY = uint32_t(y);
            path.key = uint32_t(s);
            paths.push_back(path);
        }
    });
}

// The normal, depth and cost AOVs of the primary hits.
void TileRenderer::writeAov(const TileBuffers& buf) const {
    for (size_t i = 0; i < buf.paths.size(); ++i) {
        const PathState& path = buf.paths[i];
        const Hit& hit = buf.hits[i];
        if (options_.aov == Aov::Cost) {
            film_.addCost(path.pixelX, path.pixelY, buf.costs[i].nodes + buf.costs[i].primitives);
        } else if (options_.aov == Aov::Depth) {
            film_.addDepth(path.pixelX, path.pixelY, hit.valid() ? hit.t : 0.0f);
        } else if (hit.valid()) {
            film_.addSample(path.pixelX, path.pixelY, geometry_.surface(path.ray, hit).shadingNormal * 0.5f + 0.5f);
        }
    }
}

glm::vec3 TileRenderer::segmentTransmittance(const PathState& path, float t) const {
    if (!path.media.empty()) return mediumTransmittance(scene_.materials[path.media.innermost()], t);
    return glm::vec3(fog_.transmittance(path.ray, t));
}

void TileRenderer::addLightCrossings(const PathState& path, float segment, TileBuffers& buf) const {
    buf.crossings.clear();
    lightCrossings(scene_.lights, path.ray, segment, buf.crossings);
    for (const LightCrossing& c : buf.crossings) {
        const float weight = path.scatterPdf > 0.0f ? balanceHeuristic(path.scatterPdf, float(c.count) * c.pdf) : 1.0f;
        film_.addSample(path.pixelX, path.pixelY, path.throughput() * segmentTransmittance(path, c.t) * c.radiance * weight);
    }
}

// A counting sort, stable: hits of one material stay in ray order.
void TileRenderer::sortByMaterial(TileBuffers& buf) const {
    std::vector<uint32_t>& start = buf.materialCounts;
    start.assign(scene_.materials.size() + 1, 0);
    for (const ShadingItem& item : buf.shading) ++start[item.surface.material + 1];
    for (size_t m = 1; m < start.size(); ++m) start[m] += start[m - 1];
    buf.shadingSorted.resize(buf.shading.size());
    for (const ShadingItem& item : buf.shading) buf.shadingSorted[start[item.surface.material]++] = item;
    std::swap(buf.shading, buf.shadingSorted);
}

// One bounce of every path: attenuation along the segment just traced (Beer inside a dielectric, the
// fog outside, whose in-scattered light becomes shadow samples), then the background or the surface.
void TileRenderer::shadeBounce(TileBuffers& buf) const {
    buf.shading.clear();
    for (size_t i = 0; i < buf.paths.size(); ++i) {
        PathState& path = buf.paths[i];
        const Hit& hit = buf.hits[i];
        const float segment = hit.valid() ? hit.t : INFINITY;
        SampleRng rng(path.pixelX, path.pixelY, path.key, kBouncePurpose + uint32_t(path.depth));
        if (pathTracing_) addLightCrossings(path, segment, buf);
        if (path.media.empty() && fog_.present())
            fog_.addInscattering(scene_.lights, path.ray, segment, path.throughput(), epsilon_, path.pixelX,
                                 path.pixelY, rng, buf.lightScratch, buf.shadows);
        const glm::vec3 transmittance = segmentTransmittance(path, segment);
        path.throughputS *= transmittance;
        path.throughputP *= transmittance;
        if (!hit.valid()) {
            const glm::vec3 direction(path.ray.dx, path.ray.dy, path.ray.dz);
            const glm::vec3 sky = scene_.environment ? environmentRadiance(*scene_.environment, direction) : scene_.background;
            film_.addSample(path.pixelX, path.pixelY, path.throughput() * sky);
            continue;
        }
        buf.shading.push_back({uint32_t(i), geometry_.surface(path.ray, hit), rng});
    }
    if (options_.shadingOrder == ShadingOrder::Material) sortByMaterial(buf);
    ScatterOutput out{buf.shadows, buf.nextPaths, buf.lightScratch};
    for (const ShadingItem& item : buf.shading) {
        SampleRng rng = item.rng;
        if (pathTracing_) scatterPathVertex(shading_, buf.paths[item.path], item.surface, rng, out);
        else scatterAtSurface(shading_, buf.paths[item.path], item.surface, rng, out);
    }
}

// The shadow rays of the camera hits are coherent once grouped by direction octant (rays toward one
// light from neighbouring pixels share it), so they go to the packet kernels in that order.
void TileRenderer::traceShadows(TileBuffers& buf, int depth) const {
    const bool fromCameraHits = depth == 0;
    const size_t n = buf.shadows.size();
    buf.shadowOrder.resize(n);
    for (size_t i = 0; i < n; ++i) buf.shadowOrder[i] = uint32_t(i);
    if (fromCameraHits)
        std::stable_sort(buf.shadowOrder.begin(), buf.shadowOrder.end(), [&](uint32_t a, uint32_t b) {
            return directionOctant(buf.shadows[a].ray) < directionOctant(buf.shadows[b].ray);
        });
    buf.shadowRays.resize(n);
    for (size_t i = 0; i < n; ++i) buf.shadowRays[i] = buf.shadows[buf.shadowOrder[i]].ray;
    buf.occluded.assign(n, 0);
    tracer_.occluded(buf.shadowRays, buf.occluded, fromCameraHits ? Coherence::Coherent : Coherence::Incoherent, depth);
    film_.countShadowRays(n);
    buf.shadowBlocked.resize(n);
    for (size_t i = 0; i < n; ++i) buf.shadowBlocked[buf.shadowOrder[i]] = buf.occluded[i];
    for (size_t i = 0; i < n; ++i)
        if (!buf.shadowBlocked[i])
            film_.addSample(buf.shadows[i].pixelX, buf.shadows[i].pixelY, buf.shadows[i].contribution);
}

void TileRenderer::render(const TileRect& tile, TileBuffers& buf) const {
    startPaths(tile, buf.paths);
    for (int bounce = 0; !buf.paths.empty(); ++bounce) {
        const size_t n = buf.paths.size();
        buf.rays.resize(n);
        for (size_t i = 0; i < n; ++i) buf.rays[i] = buf.paths[i].ray;
        buf.hits.assign(n, Hit{});
        if (bounce >= buf.firstRecorded && bounce <= buf.lastRecorded)
            buf.recorded.insert(buf.recorded.end(), buf.rays.begin(), buf.rays.end());
        const bool primary = bounce == 0;
        const bool cost = primary && options_.aov == Aov::Cost;
        if (cost) buf.costs.assign(n, TraversalCost{});
        tracer_.intersect(buf.rays, buf.hits, primary ? Coherence::Coherent : Coherence::Incoherent,
                          cost ? buf.costs.data() : nullptr);
        if (primary) film_.countPrimaryRays(n);
        else film_.countSecondaryRays(n);
        if (options_.aov != Aov::Color) {
            writeAov(buf);
            break;
        }
        buf.shadows.clear();
        buf.nextPaths.clear();
        shadeBounce(buf);
        traceShadows(buf, bounce);
        std::swap(buf.paths, buf.nextPaths);
    }
}

} // namespace wideray
