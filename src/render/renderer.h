#pragma once
// The tiled renderer: tiles in Hilbert order on oneTBB. Within a tile, paths advance wavefront style:
// the primary rays (Morton order) are traced as one coherent batch, every later bounce's reflected
// and refracted rays as one incoherent batch, and each bounce's shadow rays (surfaces and fog) as
// another. Shading is in src/shading/surface_scattering.h and fog_medium.h.
#include <cstdint>
#include <string>

#include "core/image.h"
#include "core/scene.h"
#include "backends/tracer.h"

namespace wideray {

enum class Aov { Color, Normal, Depth, Cost };

struct RenderOptions {
    int width = 0, height = 0;  ///< 0: the scene's
    int samplesPerPixel = 0;    ///< 0: the scene's
    Aov aov = Aov::Color;
    int tileSize = 16;          ///< a power of two
    bool progress = false;      ///< report progress on stderr once a render takes over a second
    std::string label;          ///< names the render in progress lines
};

struct RenderStats {
    double seconds = 0;
    uint64_t primaryRays = 0;
    uint64_t secondaryRays = 0;  ///< reflected and refracted
    uint64_t shadowRays = 0;
    uint64_t maxCost = 0;  ///< cost AOV: the largest per-pixel traversal cost
    uint64_t totalRays() const { return primaryRays + secondaryRays + shadowRays; }
    double mraysPerSecond() const { return seconds > 0 ? double(totalRays()) / seconds * 1e-6 : 0.0; }
};

/// Renders `scene` through `tracer`, whose geometry is the scene's.
/// The color AOV is linear RGB; normal is n * 0.5 + 0.5; depth is the first hit's t (0 on a miss);
/// cost is a heatmap of nodes + primitives visited by the primary rays, scaled to the image maximum.
Image render(const Scene& scene, const Tracer& tracer, const RenderOptions& options, RenderStats& stats);

} // namespace wideray
