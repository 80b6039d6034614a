#pragma once
// The kinds of geometry a scene can hold, one row each: the geometry that a scene's objects of that
// kind become. geomIds follow the rows: the first row, the triangles, is always geomId 0 (empty if
// the scene has none); later rows take the next id when the scene has objects of their kind. A new
// primitive type adds its scene-file parse function (io/scene_parser.cpp) and a row here.
#include <memory>
#include <span>
#include <vector>

#include "core/geometry.h"
#include "core/scene.h"

namespace wideray {

struct GeometryKind {
    const char* name;
    /// The scene's geometry of this kind; null when it has none. `twoLevel` marks the meshes whose
    /// instances are two-level (twoLevelMeshes).
    std::unique_ptr<Geometry> (*make)(const SceneDescription& scene, const std::vector<bool>& twoLevel);
};

std::span<const GeometryKind> geometryKinds();

} // namespace wideray
