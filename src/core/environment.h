#pragma once
// An environment map: the radiance arriving from infinitely far away in every direction, held in an
// image (pbrt's "infinite" light with a file). Rays that leave the scene see it; evaluation is in
// shading/environment.h.
#include <filesystem>
#include <memory>

#include <glm/glm.hpp>

#include "core/image.h"

namespace wideray {

/// How directions map to the image, both with +z up in the map's own space.
enum class EnvironmentMapping {
    LatLong,    ///< equirectangular (pbrt-v3): x the angle about z from +x, y the angle from +z down
    EqualArea,  ///< Clarberg's equal-area square (pbrt-v4): +z at the center, -z at the corners
};

struct EnvironmentMap {
    std::filesystem::path file;
    std::shared_ptr<const Image> image;
    EnvironmentMapping mapping = EnvironmentMapping::LatLong;
    glm::vec3 scale{1.0f};      ///< multiplies every pixel
    glm::mat3 toWorld{1.0f};    ///< the map's directions into the world, as given to orient()
    glm::mat3 fromWorld{1.0f};  ///< its inverse: world directions into the map's space

    /// Turns the map by an invertible linear transform from its space into the world's.
    void orient(const glm::mat3& mapToWorld) {
        toWorld = mapToWorld;
        fromWorld = glm::inverse(mapToWorld);
    }
};

} // namespace wideray
