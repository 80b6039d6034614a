#pragma once
// What the micro benchmarks run on: the shared real meshes when present ($WIDERAY_SCENES, else the
// folder the build was configured with), generated meshes otherwise, and seeded random data.
#include <cstdlib>
#include <filesystem>
#include <map>
#include <optional>
#include <random>
#include <string>
#include <system_error>

#include "core/bounds.h"
#include "core/mesh.h"
#include "core/mesh_io.h"
#include "core/scene.h"

namespace wideray::perf {

/// $WIDERAY_SCENES, else WIDERAY_DEFAULT_SCENES_DIR; nullopt when that is not a directory.
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

/// The shared mesh at `relative` inside the scenes folder, if it exists there.
inline std::optional<std::filesystem::path> sharedMeshPath(const std::string& relative) {
    auto dir = sharedScenesDir();
    if (!dir) return std::nullopt;
    std::error_code error;
    std::filesystem::path file = *dir / relative;
    if (!std::filesystem::is_regular_file(file, error)) return std::nullopt;
    return file;
}

/// Loads a mesh once per process; benchmarks run one at a time, so no locking.
inline const TriangleMesh& cachedMesh(const std::filesystem::path& file) {
    static std::map<std::filesystem::path, TriangleMesh> meshes;
    auto it = meshes.find(file);
    if (it == meshes.end()) it = meshes.emplace(file, loadMesh(file)).first;
    return it->second;
}

/// A bare mesh placed in a scene by the framing rule of `wideray bench` (core/mesh_framing.h),
/// for generated meshes that have no file.
inline Scene framedScene(TriangleMesh mesh, int width, int height) {
    Scene scene;
    scene.materials.push_back({"default", MaterialType::Diffuse, glm::vec3(0.8f)});
    mesh.faceMaterial.assign(mesh.triangles.size(), 0);
    mesh.materials.clear();
    Bounds3f b;
    for (const glm::vec3& p : mesh.positions) b.grow(p);
    scene.meshes.push_back(std::move(mesh));
    scene.instances.push_back({});
    glm::vec3 c = b.center();
    float R = 0.5f * glm::length(b.extent());
    scene.camera.position = c + glm::normalize(glm::vec3(0.3f, 0.25f, 1.0f)) * (1.2f * R);
    scene.camera.lookAt = c;
    scene.camera.fovY = 50.0f;
    scene.image = {width, height, 1};
    Light light;
    light.position = c + glm::vec3(0.5f * R, 2.0f * R, 0.7f * R);
    scene.lights.push_back(light);
    return scene;
}

/// Seeded uniform floats, so every run measures the same data.
struct RandomFloats {
    std::mt19937 engine{12345};
    float operator()(float lo, float hi) { return std::uniform_real_distribution<float>(lo, hi)(engine); }
};

} // namespace wideray::perf
