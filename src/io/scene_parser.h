#pragma once
// Reading and writing scene files (JSON; the format is described in docs/scene-format.md).
#include <filesystem>
#include <optional>
#include <string>

#include "core/scene.h"

namespace wideray {

/// The bytes of a scene file (JSON or pbrt); throws InputError when it cannot be read.
std::string readSceneText(const std::filesystem::path& file);

/// Reads and parses a scene file. Throws InputError for anything wrong with it or the meshes it uses.
SceneDescription loadScene(const std::filesystem::path& file);

/// The last frame number an animation may have (frames are 0..kLastFrame).
inline constexpr int kLastFrame = 999999;

struct FrameRange {
    int first, last;  ///< inclusive
};

/// The frames of a scene file's animation, without loading its meshes; none for a still scene.
/// Throws InputError as loadScene does for anything wrong in its "camera" or "animation".
std::optional<FrameRange> loadSceneFrames(const std::filesystem::path& file);

/// Parses scene JSON. `file` names the scene in error messages, and relative mesh paths are
/// resolved against its folder. Throws InputError naming "line L, column C" for JSON syntax errors
/// and the key path (such as "objects[2].transform.scale") for everything else.
SceneDescription parseScene(const std::string& jsonText, const std::filesystem::path& file);

/// Writes a scene as JSON that parseScene reads back into an equal scene. Meshes are written inline
/// (as "meshes" entries with their vertices and triangles), so the result needs no mesh files.
std::string writeScene(const SceneDescription& scene);

} // namespace wideray
