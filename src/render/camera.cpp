#include "render/camera.h"

#include <cmath>

namespace wideray {
namespace {

/// Maps the unit square onto the unit disk keeping strata compact (Shirley and Chiu 1997, "A
/// Low Distortion Map Between Disk and Square").
glm::vec2 concentricDisk(glm::vec2 u) {
    const glm::vec2 p = 2.0f * u - 1.0f;
    if (p.x == 0.0f && p.y == 0.0f) return glm::vec2(0.0f);
    const float quarterPi = float(M_PI) * 0.25f;
    if (std::abs(p.x) > std::abs(p.y)) {
        const float phi = quarterPi * (p.y / p.x);
        return p.x * glm::vec2(std::cos(phi), std::sin(phi));
    }
    const float phi = 2.0f * quarterPi - quarterPi * (p.x / p.y);
    return p.y * glm::vec2(std::cos(phi), std::sin(phi));
}

} // namespace

CameraModel::CameraModel(const Camera& camera, int width, int height) {
    origin_ = camera.position;
    forward_ = glm::normalize(camera.lookAt - camera.position);
    right_ = glm::normalize(glm::cross(forward_, camera.up));
    up_ = glm::cross(right_, forward_);
    scaleY_ = std::tan(glm::radians(camera.fovY) * 0.5f);
    scaleX_ = scaleY_ * float(width) / float(height);
    invWidth_ = 1.0f / float(width);
    invHeight_ = 1.0f / float(height);
    lensRadius_ = camera.aperture;
    focusDistance_ = camera.focusDistance > 0.0f ? camera.focusDistance : glm::length(camera.lookAt - camera.position);
    shutterOpen_ = camera.shutterOpen;
    shutterClose_ = camera.shutterClose;
}

Ray CameraModel::generate(float px, float py, glm::vec2 lens, float shutter) const {
    float sx = (2.0f * px * invWidth_ - 1.0f) * scaleX_;
    float sy = (1.0f - 2.0f * py * invHeight_) * scaleY_;
    glm::vec3 o = origin_;
    glm::vec3 d = glm::normalize(forward_ + sx * right_ + sy * up_);
    if (lensRadius_ > 0.0f) {
        // Every ray through this pixel meets the pinhole ray on the plane of focus.
        const glm::vec3 focus = origin_ + d * (focusDistance_ / glm::dot(d, forward_));
        const glm::vec2 disk = lensRadius_ * concentricDisk(lens);
        o = origin_ + disk.x * right_ + disk.y * up_;
        d = glm::normalize(focus - o);
    }
    Ray r;
    r.ox = o.x; r.oy = o.y; r.oz = o.z;
    r.dx = d.x; r.dy = d.y; r.dz = d.z;
    r.time = shutterOpen_ + shutter * (shutterClose_ - shutterOpen_);
    return r;
}

} // namespace wideray
