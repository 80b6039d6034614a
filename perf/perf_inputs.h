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
#include <vector>

#include <glm/glm.hpp>

#include "core/mesh.h"
#include "io/mesh_io.h"
#include "core/ray.h"
#include "core/scene.h"
#include "test_data.h"

namespace wideray::perf {

using wideray::sharedScenesDir;


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

/// Seeded uniform floats, so every run measures the same data.
struct RandomFloats {
    std::mt19937 engine{12345};
    float operator()(float lo, float hi) { return std::uniform_real_distribution<float>(lo, hi)(engine); }
};

/// Rays from a sphere of radius 4 about the origin toward random points of the cube [-spread, spread]^3.
inline std::vector<Ray> raysIntoCube(RandomFloats& random, size_t count, float spread) {
    std::vector<Ray> rays;
    for (size_t i = 0; i < count; ++i) {
        glm::vec3 o = 4.0f * glm::normalize(glm::vec3(random(-1, 1), random(-1, 1), random(-1, 1)));
        glm::vec3 d = glm::vec3(random(-spread, spread), random(-spread, spread), random(-spread, spread)) - o;
        rays.push_back({o.x, o.y, o.z, d.x, d.y, d.z, 0.0f, __builtin_huge_valf()});
    }
    return rays;
}

} // namespace wideray::perf
