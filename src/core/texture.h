#pragma once
// Textures as a scene describes them: colors (or numbers) that vary over a surface. Procedural
// patterns are solid, functions of the world position; images are looked up by the surface's uv.
// Their evaluation is in shading/texture.h.
#include <filesystem>
#include <memory>

#include <glm/glm.hpp>

#include "core/image.h"

namespace wideray {

enum class TextureType { Checker, Noise, Fbm, Turbulence, Marble, Image };

/// A texture as the scene describes it. A pattern blends `color0` into `color1` by its value at
/// `scale` times the position: the checker alternates them in cubes of side 1/scale; noise, fbm and
/// marble map [-1, 1] and turbulence [0, 1] onto them. An image holds the pixels of `file`.
struct Texture {
    TextureType type = TextureType::Checker;
    glm::vec3 color0{0.0f}, color1{1.0f};
    float scale = 1.0f;
    int octaves = 4;  ///< fbm, turbulence, marble
    std::filesystem::path file;
    std::shared_ptr<const Image> image;
};

} // namespace wideray
