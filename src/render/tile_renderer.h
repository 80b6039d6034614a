#pragma once
// One tile of a render, wavefront style: the tile's primary rays (Morton order) are traced as one
// coherent batch, every later bounce's reflected and refracted rays as one incoherent batch, and each
// bounce's shadow rays (surfaces and fog) as another. Shading is in src/shading/surface_scattering.h
// and fog_medium.h; the results go to a Film.
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

class TileRenderer {
public:
    /// `options` has the image size and samples per pixel resolved (none is 0).
    TileRenderer(const Scene& scene, const Tracer& tracer, const RenderOptions& options, const TileOrder& order,
                 Film& film);

    /// Renders one tile into the film; threads render different tiles at once, each with its buffers.
    void render(const TileRect& tile, TileBuffers& buf) const;

private:
    void startPaths(const TileRect& tile, std::vector<PathState>& paths) const;
    void writeAov(const TileBuffers& buf) const;
    void shadeBounce(TileBuffers& buf) const;
    void traceShadows(TileBuffers& buf, int depth) const;

    const Scene& scene_;
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
};

} // namespace wideray
