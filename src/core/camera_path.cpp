#include "core/camera_path.h"

#include <algorithm>

namespace wideray {
namespace {

using Vec = glm::dvec3;

/// The tangent (change per frame) of the key values `value(k)` at key i: a central difference over
/// the neighbouring keys, one-sided at the ends.
template <class Value>
Vec tangent(const std::vector<CameraKey>& keys, size_t i, Value value) {
    const size_t a = i == 0 ? 0 : i - 1, b = std::min(i + 1, keys.size() - 1);
    return (Vec(value(keys[b])) - Vec(value(keys[a]))) / double(keys[b].frame - keys[a].frame);
}

template <class Value>
glm::vec3 hermite(const std::vector<CameraKey>& keys, size_t i, double s, Value value) {
    const double h = double(keys[i + 1].frame - keys[i].frame);
    const double s2 = s * s, s3 = s2 * s;
    const Vec p0(value(keys[i])), p1(value(keys[i + 1]));
    const Vec m0 = tangent(keys, i, value) * h, m1 = tangent(keys, i + 1, value) * h;
    return glm::vec3((2 * s3 - 3 * s2 + 1) * p0 + (s3 - 2 * s2 + s) * m0 + (3 * s2 - 2 * s3) * p1 + (s3 - s2) * m1);
}

float lerp(float a, float b, double s) { return float(double(a) + (double(b) - double(a)) * s); }

} // namespace

Camera cameraAtFrame(const Animation& animation, int frame) {
    const std::vector<CameraKey>& keys = animation.keys;
    if (frame <= keys.front().frame) return keys.front().camera;
    if (frame >= keys.back().frame) return keys.back().camera;
    const auto next = std::upper_bound(keys.begin(), keys.end(), frame,
                                       [](int f, const CameraKey& key) { return f < key.frame; });
    const size_t i = size_t(next - keys.begin()) - 1;
    if (keys[i].frame == frame) return keys[i].camera;

    const double s = double(frame - keys[i].frame) / double(keys[i + 1].frame - keys[i].frame);
    const Camera &from = keys[i].camera, &to = keys[i + 1].camera;
    Camera camera = from;
    camera.position = hermite(keys, i, s, [](const CameraKey& k) { return k.camera.position; });
    camera.lookAt = hermite(keys, i, s, [](const CameraKey& k) { return k.camera.lookAt; });
    camera.up = hermite(keys, i, s, [](const CameraKey& k) { return k.camera.up; });
    camera.fovY = lerp(from.fovY, to.fovY, s);
    camera.aperture = lerp(from.aperture, to.aperture, s);
    camera.focusDistance = lerp(from.focusDistance, to.focusDistance, s);
    return camera;
}

} // namespace wideray
