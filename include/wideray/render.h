#pragma once
/// Rendering a scene file (wideray's JSON, docs/scene-format.md, or a bare OBJ, PLY or glTF mesh,
/// framed) into an image in memory, as `wideray render` does.
#include <string>
#include <vector>

#include "wideray/export.h"

namespace wideray {

/// What to change from the scene file; 0 or empty keeps the file's own setting.
struct RenderRequest {
    int width = 0, height = 0;
    int samplesPerPixel = 0;
    std::string integrator;  ///< "whitted" or "path"
    int threads = 0;         ///< 0: every hardware thread
};

/// Linear RGB, row by row from the top, 3 floats per pixel.
struct RenderedImage {
    int width = 0, height = 0;
    std::vector<float> rgb;
};

/// Throws wideray::Error naming the file and what is wrong with it.
WIDERAY_API RenderedImage renderSceneFile(const std::string& path, const RenderRequest& request = {});

} // namespace wideray
