#pragma once
// pbrt's materials, textures and colors in terms of ours (io/pbrt_parser.h): matte/diffuse,
// plastic/substrate/coateddiffuse, metal/conductor, mirror, glass/dielectric, uber; imagemap,
// constant, checkerboard, fbm and marble textures; rgb, named metal spectra and sampled spectra.
// What has no counterpart is approximated or dropped and said so through `warn`.
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>

#include "core/scene.h"
#include "io/pbrt_params.h"

namespace wideray {

/// A named texture: one of ours, or a constant.
struct PbrtTexture {
    std::optional<Texture> texture;
    glm::vec3 constant{0.5f};
};

/// Images loaded so far, by path and decoding (sRGB or linear), each loaded once.
using PbrtTextureImages = std::map<std::pair<std::filesystem::path, bool>, std::shared_ptr<const Image>>;
/// Reports what is approximated or skipped, once per key.
using PbrtWarn = std::function<void(int line, const std::string& key, const std::string& message)>;

struct PbrtMaterialContext {
    const std::map<std::string, PbrtTexture>& textures;
    PbrtWarn warn;
};

/// pbrt's default material (matte, 0.5).
Material pbrtDefaultMaterial();

/// The material of a Material or MakeNamedMaterial directive; none for an invisible one (pbrt-v4
/// "interface", an uber with opacity 0), whose shapes are left out.
std::optional<Material> pbrtMaterial(const std::string& type, const PbrtParams& params, int line,
                                     const PbrtMaterialContext& context);

/// A Texture directive's texture ("spectrum" textures decode images as sRGB, "float" ones do not).
PbrtTexture pbrtTexture(const std::string& type, const std::string& valueType, const PbrtParams& params,
                        const std::filesystem::path& folder, int line, PbrtTextureImages& images, const PbrtWarn& warn);

/// A color parameter (rgb, color, spectrum, blackbody) in RGB, or `fallback` when absent.
glm::vec3 pbrtColor(const PbrtParams& params, const std::string& name, glm::vec3 fallback,
                    const PbrtMaterialContext& context);

} // namespace wideray
