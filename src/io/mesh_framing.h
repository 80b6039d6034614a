#pragma once
// A bare mesh (OBJ, PLY, glTF) made into a scene by a documented rule, so that anyone can reproduce
// benchmark numbers on it: c = center and R = half the diagonal of the mesh bounds;
// eye = c + normalize(0.3, 0.25, 1.0) * 1.2 R; look at c; up (0, 1, 0); vertical field of view 50
// degrees; a point light at c + (0.5 R, 2 R, 0.7 R); one grey diffuse material.
#include <filesystem>
#include <optional>

#include "core/scene.h"
#include "io/scene_parser.h"

namespace wideray {

SceneDescription sceneFromMesh(const std::filesystem::path& meshFile, int width, int height);
/// The same rule for a mesh in memory (a generated one, say).
SceneDescription sceneFromMesh(TriangleMesh mesh, int width, int height);

/// Whether `file` is a scene file (.json or .pbrt, in any case) rather than a mesh.
bool isSceneFile(const std::filesystem::path& file);

/// The frames of a scene file's animation without loading its meshes (JSON scenes; pbrt scenes and
/// meshes have none).
std::optional<FrameRange> sceneFileFrames(const std::filesystem::path& file);

/// How a bare mesh becomes a scene: by the benchmark's rule above, or as a view of the model for
/// people to look at (showcaseMesh).
enum class MeshFraming { Benchmark, Showcase };

/// A bare mesh seen whole, as its author made it: its bounding sphere (center c, radius R = half the
/// box's diagonal) fills the narrower field of view (40 degrees vertical) with a 5% margin, seen from
/// the benchmark's direction c + normalize(0.3, 0.25, 1.0) d; the mesh file's materials (OBJ Kd and
/// map_Kd where the mesh has uvs, glTF baseColorFactor and a baseColorTexture of its own file), one
/// grey where it has none (white under PLY vertex colors, which tint every material); the benchmark's
/// key light, a fill light at the camera (a third of the key's light on the model, so that what the
/// key leaves in shadow is not black) and a sky-blue background, which the path tracer also takes as
/// a constant sky. `file` resolves texture paths; images that cannot be read are reported in
/// `warnings`.
SceneDescription showcaseMesh(TriangleMesh mesh, const std::filesystem::path& file, int width, int height);

/// A scene file (.json, .pbrt) as it is, or a bare mesh made into a scene as `framing` says.
SceneDescription loadSceneOrMesh(const std::filesystem::path& file, int meshWidth = 1024, int meshHeight = 1024,
                                 MeshFraming framing = MeshFraming::Benchmark);

} // namespace wideray
