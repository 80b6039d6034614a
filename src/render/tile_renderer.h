#pragma once
// One tile of a render, wavefront style: the tile's primary rays (Morton order) are traced as one
// coherent batch, every later bounce's rays as one incoherent batch, and each bounce's shadow rays
// (surfaces and fog) as another. A bounce first follows every path along the segment it traced
// (attenuation, fog, the background, and for the path tracer the area lights it crossed), then shades
// the surfaces reached, in the options' shading order. Shading is in src/shading/ (surface_scattering.h
// for the Whitted integrator, path_vertex.h for the path tracer, fog_medium.h); results go to a Film.
#include <vector>

#include "backends/tracer.h"
#include "core/scene.h"
#include "render/camera.h"
#include "render/film.h"
#include "render/tile_order.h"
#include "shading/fog_medium.h"
#include "shading/path_state.h"
#include "shading/surface_scattering.h"

namespace wideray {

/// A hit waiting to be shaded.
struct ShadingItem {
    uint32_t path;  ///< in TileBuffers::paths
    SurfacePoint surface;
    SampleRng rng{0, 0, 0};  ///< the path's random numbers for this bounce, as far as the segment used them
};

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
    std::vector<LightCrossing> crossings;
    std::vector<ShadingItem> shading, shadingSorted;  ///< the bounce's hits to shade
    std::vector<uint32_t> materialCounts;

    /// Where set, the rays of bounces firstRecorded..lastRecorded (0: camera rays) are appended to
    /// `recorded`, as they are traced (bench's bounce rays).
    int firstRecorded = -1, lastRecorded = -1;
    std::vector<Ray> recorded;
};

/// The tile size `render` uses: 16 for the Whitted integrator; for the path tracer, large enough
/// that a tile's paths (pixels x samples) make a stream of at least 4096 rays, up to 64.
int renderTileSize(const SceneDescription& scene, int samplesPerPixel);

class TileRenderer {
public:
    /// `options` has the image size and samples per pixel resolved (none is 0).
    TileRenderer(const SceneDescription& scene, const Tracer& tracer, const RenderOptions& options, const TileOrder& order,
                 Film& film);

    /// Renders one tile into the film; threads render different tiles at once, each with its buffers.
    void render(const TileRect& tile, TileBuffers& buf) const;

private:
    void startPaths(const TileRect& tile, std::vector<PathState>& paths) const;
    void writeAov(const TileBuffers& buf) const;
    void shadeBounce(TileBuffers& buf) const;
    /// The transmittance of the medium `path` is in (a dielectric's, or the fog) over [0, t] of its ray.
    glm::vec3 segmentTransmittance(const PathState& path, float t) const;
    /// Path tracing: the light of the area lights that `path` crosses before `segment`.
    void addLightCrossings(const PathState& path, float segment, TileBuffers& buf) const;
    void sortByMaterial(TileBuffers& buf) const;
    void traceShadows(TileBuffers& buf, int depth) const;

    const SceneDescription& scene_;
    const Tracer& tracer_;
    const SceneGeometry& geometry_;
    RenderOptions options_;
    const TileOrder& order_;
    Film& film_;
    CameraModel camera_;
    Bounds3f objects_;  ///< the box around the scene's geometry
    float epsilon_;     ///< how far secondary rays start from their surface
    FogMedium fog_;
    ShadingContext shading_;
    bool pathTracing_;
};

} // namespace wideray
