#include "core/camera.h"

#include <cmath>

namespace wideray {

CameraModel::CameraModel(const Camera& camera, int width, int height) {
    origin_ = camera.position;
    forward_ = glm::normalize(camera.lookAt - camera.position);
    right_ = glm::normalize(glm::cross(forward_, camera.up));
    up_ = glm::cross(right_, forward_);
    scaleY_ = std::tan(glm::radians(camera.fovY) * 0.5f);
    scaleX_ = scaleY_ * float(width) / float(height);
    invWidth_ = 1.0f / float(width);
    invHeight_ = 1.0f / float(height);
}

Ray CameraModel::generate(float px, float py) const {
    float sx = (2.0f * px * invWidth_ - 1.0f) * scaleX_;
    float sy = (1.0f - 2.0f * py * invHeight_) * scaleY_;
    glm::vec3 d = glm::normalize(forward_ + sx * right_ + sy * up_);
    Ray r;
    r.ox = origin_.x; r.oy = origin_.y; r.oz = origin_.z;
    r.dx = d.x; r.dy = d.y; r.dz = d.z;
    return r;
}

} // namespace wideray
