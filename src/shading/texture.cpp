// Texture evaluation: solid procedural patterns and bilinear image lookup.
#include "shading/texture.h"

#include <algorithm>
#include <cmath>

#include "shading/perlin_noise.h"

namespace wideray {
namespace {

/// 0 or 1, alternating between neighbouring unit cubes.
float checker(const glm::vec3& p) {
    const glm::vec3 cell = glm::floor(p);
    return std::fmod(std::abs(cell.x + cell.y + cell.z), 2.0f);
}

/// Where between color0 (0) and color1 (1) a procedural texture is at `position`.
float patternValue(const Texture& texture, const glm::vec3& position) {
    const glm::vec3 p = position * texture.scale;
    switch (texture.type) {
    case TextureType::Checker: return checker(p);
    case TextureType::Noise: return 0.5f * (perlinNoise(p) + 1.0f);
    case TextureType::Fbm: return 0.5f * (fbm(p, texture.octaves) + 1.0f);
    case TextureType::Turbulence: return turbulence(p, texture.octaves);
    case TextureType::Marble: return 0.5f * (marble(p, texture.octaves) + 1.0f);
    case TextureType::Image: break;
    }
    return 0.0f;
}

glm::vec3 texel(const Image& image, int x, int y) {
    const float* c = image.at(x, y);
    return image.channels >= 3 ? glm::vec3(c[0], c[1], c[2]) : glm::vec3(c[0]);
}

/// Bilinear lookup with wrap-around; pixel centers sit at half-integer coordinates.
glm::vec3 bilinear(const Image& image, glm::vec2 uv) {
    if (image.width == 0 || image.height == 0) return glm::vec3(0.0f);
    if (!std::isfinite(uv.x) || !std::isfinite(uv.y)) uv = glm::vec2(0.0f);
    uv -= glm::floor(uv);
    const float x = uv.x * float(image.width) - 0.5f, y = (1.0f - uv.y) * float(image.height) - 0.5f;
    const float x0 = std::floor(x), y0 = std::floor(y);
    const float fx = x - x0, fy = y - y0;
    auto wrap = [](int i, int n) { return (i % n + n) % n; };
    const int xa = wrap(int(x0), image.width), xb = wrap(int(x0) + 1, image.width);
    const int ya = wrap(int(y0), image.height), yb = wrap(int(y0) + 1, image.height);
    const glm::vec3 top = glm::mix(texel(image, xa, ya), texel(image, xb, ya), fx);
    const glm::vec3 bottom = glm::mix(texel(image, xa, yb), texel(image, xb, yb), fx);
    return glm::mix(top, bottom, fy);
}

} // namespace

glm::vec3 evaluateColor(const Texture& texture, const glm::vec3& position, const glm::vec2& uv) {
    if (texture.type == TextureType::Image) return texture.image ? bilinear(*texture.image, uv) : glm::vec3(0.0f);
    const float t = std::clamp(patternValue(texture, position), 0.0f, 1.0f);
    return glm::mix(texture.color0, texture.color1, t);
}

float evaluateScalar(const Texture& texture, const glm::vec3& position, const glm::vec2& uv) {
    return evaluateColor(texture, position, uv).x;
}

} // namespace wideray
