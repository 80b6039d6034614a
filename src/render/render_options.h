#pragma once
// What a render is asked for, and what it reports.
#include <cstdint>
#include <string>

namespace wideray {

enum class Aov { Color, Normal, Depth, Cost };

/// The order in which a bounce's hits are shaded: as their rays were traced, or grouped by material
/// (Afra, Benthin, Wald and Munkberg 2016, "Local Shading Coherence Extraction for SIMD-Efficient
/// Path Tracing on CPUs"), so that consecutive hits run the same shading code on the same data.
enum class ShadingOrder { Ray, Material };

struct RenderOptions {
    int width = 0, height = 0;  ///< 0: the scene's
    int samplesPerPixel = 0;    ///< 0: the scene's
    Aov aov = Aov::Color;
    int tileSize = 0;           ///< a power of two; 0: chosen (renderTileSize)
    ShadingOrder shadingOrder = ShadingOrder::Material;
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

} // namespace wideray
