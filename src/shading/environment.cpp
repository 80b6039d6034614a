#include "shading/environment.h"

#include <algorithm>
#include <cmath>

#include <glm/gtc/constants.hpp>

namespace wideray {

glm::vec2 environmentUv(EnvironmentMapping mapping, glm::vec3 d) {
    d = glm::normalize(d);
    if (mapping == EnvironmentMapping::LatLong) {
        float phi = std::atan2(d.y, d.x);
        if (phi < 0.0f) phi += glm::two_pi<float>();
        const float theta = std::acos(std::clamp(d.z, -1.0f, 1.0f));
        return {phi / glm::two_pi<float>(), theta / glm::pi<float>()};
    }
    // Clarberg, "Fast equal-area mapping of the (hemi)sphere using SIMD" (2008), as pbrt-v4 writes it.
    const float x = std::abs(d.x), y = std::abs(d.y), z = std::abs(d.z);
    const float r = std::sqrt(std::max(0.0f, 1.0f - z));
    const float a = std::max(x, y), b = a == 0.0f ? 0.0f : std::min(x, y) / a;
    float phi = std::atan(b) * 2.0f / glm::pi<float>();
    if (x < y) phi = 1.0f - phi;
    float v = phi * r, u = r - v;
    if (d.z < 0.0f) {
        std::swap(u, v);
        u = 1.0f - u;
        v = 1.0f - v;
    }
    u = std::copysign(u, d.x);
    v = std::copysign(v, d.y);
    return {0.5f * (u + 1.0f), 0.5f * (v + 1.0f)};
}

glm::vec3 environmentRadiance(const EnvironmentMap& map, glm::vec3 direction) {
    const Image& image = *map.image;
    const glm::vec2 uv = environmentUv(map.mapping, map.fromWorld * direction);
    // Pixel centers at half-integers; longitude wraps around in a lat-long map, the rest clamps.
    const float fx = uv.x * float(image.width) - 0.5f, fy = uv.y * float(image.height) - 0.5f;
    if (!std::isfinite(fx) || !std::isfinite(fy)) return glm::vec3(0.0f);
    const int x0 = int(std::floor(fx)), y0 = int(std::floor(fy));
    const float tx = fx - float(x0), ty = fy - float(y0);
    const bool wrapX = map.mapping == EnvironmentMapping::LatLong;
    auto column = [&](int x) { return wrapX ? (x % image.width + image.width) % image.width : std::clamp(x, 0, image.width - 1); };
    auto texel = [&](int x, int y) {
        const float* p = image.at(column(x), std::clamp(y, 0, image.height - 1));
        return image.channels >= 3 ? glm::vec3(p[0], p[1], p[2]) : glm::vec3(p[0]);
    };
    const glm::vec3 top = glm::mix(texel(x0, y0), texel(x0 + 1, y0), tx);
    const glm::vec3 bottom = glm::mix(texel(x0, y0 + 1), texel(x0 + 1, y0 + 1), tx);
    return map.scale * glm::mix(top, bottom, ty);
}

} // namespace wideray
