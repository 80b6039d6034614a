#pragma once
// Looking up an environment map (core/environment.h) in a direction.
#include <glm/glm.hpp>

#include "core/environment.h"

namespace wideray {

/// Where a direction of the map's space (need not be unit length) falls in its image: [0, 1]^2, with
/// y = 0 the image's top row.
glm::vec2 environmentUv(EnvironmentMapping mapping, glm::vec3 direction);

/// The radiance arriving from world direction `direction`, bilinear between pixels.
glm::vec3 environmentRadiance(const EnvironmentMap& map, glm::vec3 direction);

} // namespace wideray
