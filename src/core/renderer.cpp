#include "core/renderer.h"

#include <atomic>
#include <chrono>
#include <cstdio>
#include <mutex>
#include <unistd.h>

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include "core/bounds.h"
#include "core/camera.h"
#include "core/heatmap.h"
#include "core/random.h"
#include "core/surface.h"
#include "core/tile_order.h"
#include "shading/direct_lighting.h"

namespace wideray {
namespace {

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

float sceneExtent(const TriangleMesh& world, const Scene& scene) {
    Bounds3f b;
    for (const glm::vec3& p : world.positions) b.grow(p);
    for (const Sphere& s : scene.spheres) {
        b.grow(s.center - glm::vec3(s.radius));
        b.grow(s.center + glm::vec3(s.radius));
    }
    return b.empty() ? 1.0f : glm::length(b.extent());
}

/// The work space of one tile, reused by the tiles a thread renders.
struct TileBuffers {
    std::vector<Ray> rays;
    std::vector<Hit> hits;
    std::vector<TraversalCost> costs;
    std::vector<uint32_t> rayPixel;  ///< pixel index in the tile of each primary ray
    std::vector<ShadowSample> shadows;
    std::vector<uint32_t> shadowPixel;
    std::vector<Ray> shadowRays;
    std::vector<uint8_t> occluded;
};

} // namespace

Image render(const Scene& scene, const TriangleMesh& world, const Tracer& tracer, const RenderOptions& options,
             RenderStats& stats) {
    const int width = options.width > 0 ? options.width : scene.image.width;
    const int height = options.height > 0 ? options.height : scene.image.height;
    const int spp = options.samplesPerPixel > 0 ? options.samplesPerPixel : scene.image.samplesPerPixel;
    const int tileSize = options.tileSize;
    const CameraModel camera(scene.camera, width, height);
    const float epsilon = 1e-4f * sceneExtent(world, scene);
    const std::vector<TileRect> tiles = hilbertTiles(width, height, tileSize);
    const std::vector<uint32_t> morton = mortonPixelOrder(tileSize);
    const int channels = options.aov == Aov::Depth ? 1 : 3;

    Image image(width, height, channels);
    std::vector<uint32_t> costImage(options.aov == Aov::Cost ? size_t(width) * height : 0);
    std::atomic<uint64_t> primaryRays{0}, shadowRays{0};
    tbb::enumerable_thread_specific<TileBuffers> buffers;
    ProgressReporter progress(options.progress, options.label, tiles.size());

    auto renderTile = [&](const TileRect& tile) {
        TileBuffers& buf = buffers.local();
        buf.rays.clear();
        buf.rayPixel.clear();
        for (uint32_t local : morton) {
            int x = tile.x0 + int(local % tileSize), y = tile.y0 + int(local / tileSize);
            if (x >= tile.x1 || y >= tile.y1) continue;
            for (int s = 0; s < spp; ++s) {
                float jx = 0.5f, jy = 0.5f;
                if (spp > 1) {
                    SampleRng rng(uint32_t(x), uint32_t(y), uint32_t(s), 1);
                    jx = rng.next();
                    jy = rng.next();
                }
                buf.rays.push_back(camera.generate(float(x) + jx, float(y) + jy));
                buf.rayPixel.push_back(uint32_t(y) * width + x);
            }
        }
        const size_t n = buf.rays.size();
        buf.hits.assign(n, Hit{});
        buf.costs.assign(n, TraversalCost{});
        tracer.intersect(buf.rays, buf.hits, Coherence::Coherent,
                         options.aov == Aov::Cost ? buf.costs.data() : nullptr);
        primaryRays += n;

        if (options.aov != Aov::Color) {
            for (size_t i = 0; i < n; ++i) {
                uint32_t pixel = buf.rayPixel[i];
                float* out = &image.pixels[size_t(pixel) * channels];
                const Hit& hit = buf.hits[i];
                if (options.aov == Aov::Cost) {
                    costImage[pixel] += buf.costs[i].nodes + buf.costs[i].primitives;
                } else if (options.aov == Aov::Depth) {
                    out[0] += hit.valid() ? hit.t / float(spp) : 0.0f;
                } else if (hit.valid()) {
                    glm::vec3 nrm = surfaceAt(world, tracer, buf.rays[i], hit).shadingNormal * 0.5f + 0.5f;
                    for (int c = 0; c < 3; ++c) out[c] += nrm[c] / float(spp);
                }
            }
            progress.tileDone();
            return;
        }

        buf.shadows.clear();
        buf.shadowPixel.clear();
        for (size_t i = 0; i < n; ++i) {
            uint32_t pixel = buf.rayPixel[i];
            float* out = &image.pixels[size_t(pixel) * 3];
            const Hit& hit = buf.hits[i];
            if (!hit.valid()) {
                for (int c = 0; c < 3; ++c) out[c] += scene.background[c] / float(spp);
                continue;
            }
            const Ray& ray = buf.rays[i];
            SurfacePoint sp = surfaceAt(world, tracer, ray, hit);
            glm::vec3 dir(ray.dx, ray.dy, ray.dz);
            glm::vec3 n = glm::dot(sp.shadingNormal, dir) < 0.0f ? sp.shadingNormal : -sp.shadingNormal;
            const Material& material = scene.materials[sp.material];
            SampleRng rng(pixel % uint32_t(width), pixel / uint32_t(width), uint32_t(i % spp), 2);
            size_t before = buf.shadows.size();
            sampleDirectLighting(scene.lights, sp.position, n, material.color, epsilon, rng, buf.shadows);
            buf.shadowPixel.insert(buf.shadowPixel.end(), buf.shadows.size() - before, pixel);
        }
        buf.shadowRays.resize(buf.shadows.size());
        for (size_t i = 0; i < buf.shadows.size(); ++i) buf.shadowRays[i] = buf.shadows[i].ray;
        buf.occluded.assign(buf.shadows.size(), 0);
        tracer.occluded(buf.shadowRays, buf.occluded, Coherence::Incoherent);
        shadowRays += buf.shadows.size();
        for (size_t i = 0; i < buf.shadows.size(); ++i) {
            if (buf.occluded[i]) continue;
            float* out = &image.pixels[size_t(buf.shadowPixel[i]) * 3];
            for (int c = 0; c < 3; ++c) out[c] += buf.shadows[i].contribution[c] / float(spp);
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
