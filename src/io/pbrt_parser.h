#pragma once
// Reading pbrt-v3 and pbrt-v4 scene files (docs/scene-format.md, "pbrt scenes") into a scene: camera,
// film, sampler and integrator settings, transforms and attribute blocks, triangle meshes, PLY meshes
// and spheres, materials and textures mapped onto ours, point, distant, infinite and area lights.
// What wideray does not have is reported once in SceneDescription::warnings (FILE:LINE: what) and
// skipped; malformed input throws InputError naming FILE and line.
#include <filesystem>
#include <string>

#include "core/scene.h"

namespace wideray {

SceneDescription loadPbrt(const std::filesystem::path& file);

/// `text` as the contents of `file` (Include and mesh paths are resolved against its folder).
SceneDescription parsePbrt(const std::string& text, const std::filesystem::path& file);

} // namespace wideray
