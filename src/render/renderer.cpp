#include "render/renderer.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <chrono>
#include <cstdio>
#include <mutex>
#include <unistd.h>

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include "core/bounds.h"
#include "render/camera.h"
#include "render/heatmap.h"
#include "core/random.h"
#include "shading/path_state.h"
#include "render/tile_order.h"
#include "shading/beer.h"
#include "shading/fog_medium.h"
#include "shading/surface_scattering.h"

namespace wideray {
namespace {

uint32_t directionOctant(const Ray& r) {
    return (r.dx < 0.0f ? 1u : 0u) | (r.dy < 0.0f ? 2u : 0u) | (r.dz < 0.0f ? 4u : 0u);
}

using Clock = std::chrono::steady_clock;

/// Prints "label: 42%" on stderr, at most every quarter second, once the render has run a second.
class ProgressReporter {
public:
    ProgressReporter(bool enabled, std::string label, size_t total)
        : enabled_(enabled), label_(std::move(label)), total_(total), start_(Clock::now()) {}

    void tileDone() {
        size_t done = ++done_;
        if (!enabled_) return;
        auto now = Clock::now();
        if (now - start_ < std::chrono::seconds(1)) return;
        std::unique_lock lock(mutex_, std::try_to_lock);
        if (!lock.owns_lock() || (now - lastPrint_ < std::chrono::milliseconds(250) && done != total_)) return;
        lastPrint_ = now;
        printed_ = true;
        std::fprintf(stderr, "\r%s: %3d%%", label_.c_str(), int(100 * done / total_));
        std::fflush(stderr);
    }

    ~ProgressReporter() {
        if (printed_) std::fprintf(stderr, "\r%s: 100%%\n", label_.c_str());
    }

private:
    bool enabled_;
    std::string label_;
    size_t total_;
    std::atomic<size_t> done_{0};
    Clock::time_point start_, lastPrint_;
    std::mutex mutex_;
    bool printed_ = false;
};

/// The box around the scene's objects and its lights' positions.
Bounds3f boundsWithLights(const Bounds3f& objects, const Scene& scene) {
    Bounds3f b = objects;
    for (const Light& light : scene.lights) {
        if (light.type == LightType::Directional) continue;
        b.grow(light.position - glm::vec3(light.radius));
        b.grow(light.position + glm::vec3(light.radius));
        if (light.type == LightType::Quad) b.grow(light.position + light.edgeU + light.edgeV);
    }
    return b;
}

constexpr uint32_t kCameraPurpose = 1;
/// Purposes from here on seed the random numbers of a path's bounces, one per depth.
constexpr uint32_t kBouncePurpose = 2;

/// The work space of one tile, reused by the tiles a thread renders.
struct TileBuffers {
    std::vector<PathState> paths, nextPaths;
    std::vector<Ray> rays;
    std::vector<Hit> hits;
    std::vector<TraversalCost> costs;
    std::vector<ShadowSample> shadows;
    std::vector<Ray> shadowRays;
    std::vector<uint8_t> occluded;
    std::vector<uint32_t> shadowOrder;   ///< the shadow batch sorted for tracing
    std::vector<uint8_t> shadowBlocked;  ///< occlusion per shadow sample, in the order they were made
    std::vector<LightSample> lightScratch;
};

/// The fraction of light left after a segment inside the medium of `material`; a segment that
/// never ends (an open mesh) keeps only the channels the medium does not absorb.
glm::vec3 mediumTransmittance(const Material& material, float distance) {
    if (std::isinf(distance)) return glm::vec3(glm::equal(material.absorption, glm::vec3(0.0f)));
    return beerTransmittance(material.absorption, distance);
}

} // namespace

Image render(const Scene& scene, const Tracer& tracer, const RenderOptions& options, RenderStats& stats) {
    const int width = options.width > 0 ? options.width : scene.image.width;
    const int height = options.height > 0 ? options.height : scene.image.height;
    const int spp = options.samplesPerPixel > 0 ? options.samplesPerPixel : scene.image.samplesPerPixel;
    const int tileSize = options.tileSize;
    const CameraModel camera(scene.camera, width, height);
    const SceneGeometry& geometry = tracer.geometry();
    const Bounds3f objects = geometry.bounds();
    const float epsilon = 1e-4f * (objects.empty() ? 1.0f : glm::length(objects.extent()));
    const FogMedium fog(scene.fog, boundsWithLights(objects, scene));
    const ShadingContext shading{scene, fog, epsilon};
    const std::vector<TileRect> tiles = hilbertTiles(width, height, tileSize);
    const std::vector<uint32_t> morton = mortonPixelOrder(tileSize);
    const int channels = options.aov == Aov::Depth ? 1 : 3;

    Image image(width, height, channels);
    std::vector<uint32_t> costImage(options.aov == Aov::Cost ? size_t(width) * height : 0);
    std::atomic<uint64_t> primaryRays{0}, secondaryRays{0}, shadowRays{0};
    tbb::enumerable_thread_specific<TileBuffers> buffers;
    ProgressReporter progress(options.progress, options.label, tiles.size());
    const float sampleWeight = 1.0f / float(spp);
    auto addToPixel = [&](uint32_t x, uint32_t y, const glm::vec3& color) {
        float* out = image.at(int(x), int(y));
        for (int c = 0; c < 3; ++c) out[c] += color[c] * sampleWeight;
    };

    // Primary paths of the tile in Morton order, each pixel's samples stratified over the pixel and,
    // in a rotated order, over the lens.
    auto startPaths = [&](const TileRect& tile, std::vector<PathState>& paths) {
        paths.clear();
        for (uint32_t local : morton) {
            const int x = tile.x0 + int(local % tileSize), y = tile.y0 + int(local / tileSize);
            if (x >= tile.x1 || y >= tile.y1) continue;
            const uint32_t lensRotation = pcgHash(uint32_t(y) * uint32_t(width) + uint32_t(x));
            for (int s = 0; s < spp; ++s) {
                SampleRng rng(uint32_t(x), uint32_t(y), uint32_t(s), kCameraPurpose);
                const glm::vec2 jitter = spp > 1 ? stratifiedPoint(s, spp, rng) : glm::vec2(0.5f);
                const glm::vec2 lens = stratifiedPoint(int((uint32_t(s) + lensRotation) % uint32_t(spp)), spp, rng);
                PathState path;
                path.ray = camera.generate(float(x) + jitter.x, float(y) + jitter.y, lens);
                path.pixelX = uint32_t(x);
                path.pixelY = uint32_t(y);
                path.key = uint32_t(s);
                paths.push_back(path);
            }
        }
    };

    // The normal, depth and cost AOVs of the primary hits.
    auto writeAov = [&](TileBuffers& buf) {
        for (size_t i = 0; i < buf.paths.size(); ++i) {
            const PathState& path = buf.paths[i];
            const Hit& hit = buf.hits[i];
            float* out = image.at(int(path.pixelX), int(path.pixelY));
            if (options.aov == Aov::Cost) {
                costImage[size_t(path.pixelY) * width + path.pixelX] += buf.costs[i].nodes + buf.costs[i].primitives;
            } else if (options.aov == Aov::Depth) {
                out[0] += hit.valid() ? hit.t * sampleWeight : 0.0f;
            } else if (hit.valid()) {
                addToPixel(path.pixelX, path.pixelY, geometry.surface(path.ray, hit).shadingNormal * 0.5f + 0.5f);
            }
        }
    };

    // One bounce of every path: attenuation along the segment just traced (Beer inside a dielectric,
    // the fog outside, whose in-scattered light becomes shadow samples), then the background or the
    // surface.
    auto shadeBounce = [&](TileBuffers& buf) {
        ScatterOutput out{buf.shadows, buf.nextPaths, buf.lightScratch};
        for (size_t i = 0; i < buf.paths.size(); ++i) {
            PathState& path = buf.paths[i];
            const Hit& hit = buf.hits[i];
            const float segment = hit.valid() ? hit.t : INFINITY;
            SampleRng rng(path.pixelX, path.pixelY, path.key, kBouncePurpose + uint32_t(path.depth));
            if (!path.media.empty()) {
                const glm::vec3 inside = mediumTransmittance(scene.materials[path.media.innermost()], segment);
                path.throughputS *= inside;
                path.throughputP *= inside;
            } else if (fog.present()) {
                fog.addInscattering(scene.lights, path.ray, segment, path.throughput(), epsilon, path.pixelX,
                                    path.pixelY, rng, buf.lightScratch, buf.shadows);
                const float outside = fog.transmittance(path.ray, segment);
                path.throughputS *= outside;
                path.throughputP *= outside;
            }
            if (!hit.valid()) {
                addToPixel(path.pixelX, path.pixelY, path.throughput() * scene.background);
                continue;
            }
            scatterAtSurface(shading, path, geometry.surface(path.ray, hit), rng, out);
        }
    };

    // The shadow rays of the camera hits are coherent once grouped by direction octant (rays toward
    // one light from neighbouring pixels share it), so they go to the packet kernels in that order.
    auto traceShadows = [&](TileBuffers& buf, int depth) {
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
        tracer.occluded(buf.shadowRays, buf.occluded, fromCameraHits ? Coherence::Coherent : Coherence::Incoherent,
                        depth);
        shadowRays += n;
        buf.shadowBlocked.resize(n);
        for (size_t i = 0; i < n; ++i) buf.shadowBlocked[buf.shadowOrder[i]] = buf.occluded[i];
        for (size_t i = 0; i < n; ++i)
            if (!buf.shadowBlocked[i]) addToPixel(buf.shadows[i].pixelX, buf.shadows[i].pixelY, buf.shadows[i].contribution);
    };

    auto renderTile = [&](const TileRect& tile) {
        TileBuffers& buf = buffers.local();
        startPaths(tile, buf.paths);
        for (int bounce = 0; !buf.paths.empty(); ++bounce) {
            const size_t n = buf.paths.size();
            buf.rays.resize(n);
            for (size_t i = 0; i < n; ++i) buf.rays[i] = buf.paths[i].ray;
            buf.hits.assign(n, Hit{});
            const bool primary = bounce == 0;
            if (primary && options.aov == Aov::Cost) buf.costs.assign(n, TraversalCost{});
            tracer.intersect(buf.rays, buf.hits, primary ? Coherence::Coherent : Coherence::Incoherent,
                             primary && options.aov == Aov::Cost ? buf.costs.data() : nullptr);
            (primary ? primaryRays : secondaryRays) += n;
            if (options.aov != Aov::Color) {
                writeAov(buf);
                break;
            }
            buf.shadows.clear();
            buf.nextPaths.clear();
            shadeBounce(buf);
            traceShadows(buf, bounce);
            std::swap(buf.paths, buf.nextPaths);
        }
        progress.tileDone();
    };

    auto start = Clock::now();
    tbb::parallel_for(tbb::blocked_range<size_t>(0, tiles.size(), 1),
                      [&](const tbb::blocked_range<size_t>& r) {
                          for (size_t t = r.begin(); t != r.end(); ++t) renderTile(tiles[t]);
                      },
                      tbb::simple_partitioner());
    stats.seconds = std::chrono::duration<double>(Clock::now() - start).count();
    stats.primaryRays = primaryRays;
    stats.secondaryRays = secondaryRays;
    stats.shadowRays = shadowRays;

    if (options.aov == Aov::Cost) {
        uint32_t maxCost = 1;
        for (uint32_t c : costImage) maxCost = std::max(maxCost, c);
        stats.maxCost = maxCost;
        for (size_t p = 0; p < costImage.size(); ++p) {
            glm::vec3 c = heatmapColor(float(costImage[p]) / float(maxCost));
            for (int k = 0; k < 3; ++k) image.pixels[p * 3 + k] = c[k];
        }
    }
    return image;
}

} // namespace wideray
