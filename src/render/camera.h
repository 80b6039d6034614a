#pragma once
// Camera rays through pixel positions: a pinhole, or a thin lens for depth of field (Pharr, Jakob and
// Humphreys, "Physically Based Rendering", 3rd ed., 6.2.3).
#include <glm/glm.hpp>

#include "core/ray.h"
#include "core/scene.h"

namespace wideray {

class CameraModel {
public:
    CameraModel(const Camera& camera, int width, int height);

    /// The ray through image position (px, py) in pixels, y down; (x + 0.5, y + 0.5) is a pixel center.
    /// `lens` in [0, 1)^2 picks the point on the lens the ray leaves from; (0.5, 0.5) is its center,
    /// and a pinhole camera ignores it; `shutter` in [0, 1) picks the ray's time in the shutter
    /// interval. Directions are unit length.
    Ray generate(float px, float py, glm::vec2 lens = glm::vec2(0.5f), float shutter = 0.0f) const;
    glm::vec3 position() const { return origin_; }

private:
    glm::vec3 origin_, forward_, right_, up_;
    float scaleX_, scaleY_;
    float invWidth_, invHeight_;
    float lensRadius_, focusDistance_;
    float shutterOpen_, shutterClose_;
};

} // namespace wideray
