#pragma once
// Where tests find the shared real-world scenes (large meshes that are not in the repository).
#include <cstdlib>
#include <filesystem>
#include <optional>
#include <system_error>

namespace wideray {

/// The directory named by $WIDERAY_SCENES, else WIDERAY_DEFAULT_SCENES_DIR (defined by the build);
/// nullopt when neither names an existing directory, so tests that need it can skip.
inline std::optional<std::filesystem::path> sharedScenesDir() {
    std::filesystem::path dir;
    if (const char* fromEnvironment = std::getenv("WIDERAY_SCENES"); fromEnvironment && *fromEnvironment)
        dir = fromEnvironment;
#ifdef WIDERAY_DEFAULT_SCENES_DIR
    else
        dir = WIDERAY_DEFAULT_SCENES_DIR;
#endif
    std::error_code error;
    if (dir.empty() || !std::filesystem::is_directory(dir, error)) return std::nullopt;
    return dir;
}

/// The main file of each shared scene folder (see its README.txt), smallest first.
inline constexpr const char* kSharedMeshes[] = {
    "cornell-box/CornellBox-Original.obj", "suzanne/suzanne.obj",
    "teapot/teapot.obj", "stanford-bunny/bun_zipper.ply",
    "stanford-dragon-100k/dragon_100k.ply", "bitterli-coffee-maker/coffee_maker_merged.ply",
    "crytek-sponza/sponza.obj", "bitterli-country-kitchen/country_kitchen_merged.ply",
};

} // namespace wideray
