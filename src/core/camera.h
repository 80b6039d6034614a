#pragma once
// Pinhole camera rays through pixel positions (thin-lens depth of field is reserved in the format).
#include <glm/glm.hpp>

#include "core/ray.h"
#include "core/scene.h"

namespace wideray {

class CameraModel {
public:
    CameraModel(const Camera& camera, int width, int height);

    /// The ray through image position (px, py) in pixels, y down; (x + 0.5, y + 0.5) is a pixel center.
    Ray generate(float px, float py) const;
    glm::vec3 position() const { return origin_; }

private:
    glm::vec3 origin_, forward_, right_, up_;
    float scaleX_, scaleY_;
    float invWidth_, invHeight_;
};

} // namespace wideray
