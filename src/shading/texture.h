#pragma once
// Evaluating textures (core/texture.h describes them) at a surface point.
#include <glm/glm.hpp>

#include "core/texture.h"

namespace wideray {

/// The texture's color at a surface point. Images are sampled bilinearly at `uv`, repeating outside
/// [0, 1]; v = 0 is the bottom row. Grey images give grey colors.
glm::vec3 evaluateColor(const Texture& texture, const glm::vec3& position, const glm::vec2& uv);

/// The texture as a number (such as a roughness): the first channel of evaluateColor.
float evaluateScalar(const Texture& texture, const glm::vec3& position, const glm::vec2& uv);

} // namespace wideray
