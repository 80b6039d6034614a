#include "io/pbrt_materials.h"

#include <algorithm>
#include <cmath>

#include <fmt/core.h>

#include "core/error.h"
#include "io/image_io.h"
#include "shading/material_model.h"

namespace wideray {
namespace {

/// pbrt's named metal spectra and the measured metals we have in RGB.
std::optional<ComplexIor> namedMetal(const std::string& spectrum) {
    for (const auto& [element, ours] : {std::pair{"Cu", "copper"}, {"Au", "gold"}, {"Ag", "silver"}, {"Al", "aluminium"}})
        if (spectrum == fmt::format("metal-{}-eta", element) || spectrum == fmt::format("metal-{}-k", element))
            return conductorPreset(ours);
    return std::nullopt;
}

float mean(glm::vec3 c) { return (c.x + c.y + c.z) / 3.0f; }

/// pbrt-v3's RoughnessToAlpha for remapped roughness (the default in pbrt-v3's materials).
float pbrtV3Alpha(float roughness) {
    const float x = std::log(std::max(roughness, 1e-3f));
    return 1.62142f + 0.819955f * x + 0.1734f * x * x + 0.0171201f * x * x * x + 0.000640711f * x * x * x * x;
}

/// The microfacet alpha of a material's roughness parameters; `v3` chooses pbrt-v3's remapping
/// (v4 maps roughness r to alpha sqrt(r)).
float microfacetAlpha(const PbrtParams& p, float fallback, bool v3) {
    float r = p.number("roughness", fallback);
    if (p.has("uroughness") || p.has("vroughness")) r = 0.5f * (p.number("uroughness", r) + p.number("vroughness", r));
    const PbrtParam* remap = p.find("remaproughness");
    const bool remapped = !remap || remap->strings.empty() || remap->strings[0] == "true";
    if (!remapped) return r;
    return v3 ? pbrtV3Alpha(r) : std::sqrt(r);
}

/// Our roughness r has alpha = r^2.
float roughnessOf(float alpha) { return std::clamp(std::sqrt(std::max(alpha, 0.0f)), 0.0f, 1.0f); }

/// A Blinn-Phong exponent with the lobe width of a microfacet alpha (Walter et al. 2007: 2/alpha^2 - 2).
float shininessOf(float alpha) { return std::clamp(2.0f / std::max(alpha * alpha, 1e-6f) - 2.0f, 1.0f, 10000.0f); }

/// A color slot that may name a texture ("texture Kd") or hold a color ("rgb Kd").
void colorSlot(const PbrtParams& p, const std::string& name, glm::vec3 fallback, Material& m,
               const PbrtMaterialContext& context) {
    const PbrtParam* q = p.find(name);
    if (q && q->type == "texture") {
        auto it = q->strings.size() == 1 ? context.textures.find(q->strings[0]) : context.textures.end();
        if (it == context.textures.end())
            throw PbrtLineError{q->line, "\"texture " + name + "\" names no texture defined before"};
        if (it->second.texture) m.colorTexture = it->second.texture;
        m.color = it->second.constant;
        return;
    }
    m.color = glm::clamp(pbrtColor(p, name, fallback, context), glm::vec3(0.0f), glm::vec3(1.0f));
}

} // namespace

Material pbrtDefaultMaterial() { return {"pbrt default", MaterialType::Diffuse, glm::vec3(0.5f)}; }

glm::vec3 pbrtColor(const PbrtParams& params, const std::string& name, glm::vec3 fallback,
                    const PbrtMaterialContext& context) {
    const PbrtParam* q = params.find(name);
    if (!q) return fallback;
    if (q->type == "rgb" || q->type == "color") {
        if (q->numbers.size() != 3) throw PbrtLineError{q->line, "\"" + q->type + " " + name + "\" needs 3 numbers"};
        return glm::vec3(q->numbers[0], q->numbers[1], q->numbers[2]);
    }
    if (q->type == "float" && q->numbers.size() == 1) return glm::vec3(float(q->numbers[0]));
    if (q->type == "spectrum") {
        if (q->strings.size() == 1) {
            if (auto metal = namedMetal(q->strings[0])) return q->strings[0].ends_with("-k") ? metal->k : metal->eta;
            context.warn(q->line, "spectrum/" + q->strings[0],
                         "spectrum \"" + q->strings[0] + "\" is not one wideray knows; white instead");
            return glm::vec3(1.0f);
        }
        if (q->numbers.size() >= 2 && q->numbers.size() % 2 == 0) {
            context.warn(q->line, "spectrum/sampled", "sampled spectra are averaged into a grey");
            double sum = 0;
            for (size_t i = 1; i < q->numbers.size(); i += 2) sum += q->numbers[i];
            return glm::vec3(float(sum / double(q->numbers.size() / 2)));
        }
    }
    if (q->type == "blackbody") {
        context.warn(q->line, "blackbody", "blackbody emission is taken as white of the same brightness");
        return glm::vec3(q->numbers.size() >= 2 ? float(q->numbers[1]) : 1.0f);
    }
    throw PbrtLineError{q->line, "\"" + q->type + " " + name + "\" is not a color"};
}

std::optional<Material> pbrtMaterial(const std::string& type, const PbrtParams& p, int line,
                                     const PbrtMaterialContext& context) {
    // Materials that end early have looked at all they need.
    auto consumed = [&] {
        for (const PbrtParam& q : p.list) q.used = true;
    };
    Material m;
    m.type = MaterialType::Diffuse;
    if (type == "" || type == "none" || type == "interface") return consumed(), std::nullopt;
    if (type == "matte" || type == "diffuse") {
        colorSlot(p, type == "matte" ? "Kd" : "reflectance", glm::vec3(0.5f), m, context);
    } else if (type == "plastic" || type == "substrate" || type == "coateddiffuse") {
        m.type = MaterialType::Plastic;
        colorSlot(p, type == "coateddiffuse" ? "reflectance" : "Kd", glm::vec3(type == "plastic" ? 0.25f : 0.5f), m, context);
        const glm::vec3 ks = type == "coateddiffuse" ? glm::vec3(0.04f) : pbrtColor(p, "Ks", glm::vec3(type == "plastic" ? 0.25f : 0.5f), context);
        m.specular = std::clamp(mean(ks), 0.0f, 1.0f);
        m.shininess = shininessOf(microfacetAlpha(p, type == "coateddiffuse" ? 0.0f : 0.1f, type != "coateddiffuse"));
    } else if (type == "metal" || type == "conductor") {
        m.type = MaterialType::Conductor;
        const ComplexIor copper = *conductorPreset("copper");
        if (p.has("reflectance")) {
            // pbrt-v4's artist-friendly conductor: a mirror of that color with its roughness.
            m.type = MaterialType::Conductor;
            const glm::vec3 r = glm::clamp(pbrtColor(p, "reflectance", glm::vec3(0.9f), context), glm::vec3(0.0f), glm::vec3(0.999f));
            m.eta = glm::vec3(1.0f);
            m.k = 2.0f * glm::sqrt(r) / glm::sqrt(glm::vec3(1.0f) - r);  // Fresnel at normal incidence = r with eta 1
        } else {
            m.eta = pbrtColor(p, "eta", copper.eta, context);
            m.k = pbrtColor(p, "k", copper.k, context);
        }
        m.roughness = roughnessOf(microfacetAlpha(p, type == "metal" ? 0.01f : 0.0f, type == "metal"));
    } else if (type == "mirror") {
        m.type = MaterialType::Mirror;
        m.color = glm::clamp(pbrtColor(p, "Kr", glm::vec3(0.9f), context), glm::vec3(0.0f), glm::vec3(1.0f));
    } else if (type == "glass" || type == "dielectric" || type == "thindielectric") {
        const glm::vec3 kt = pbrtColor(p, "Kt", glm::vec3(1.0f), context);
        pbrtColor(p, "Kr", glm::vec3(1.0f), context);
        if (type == "thindielectric") context.warn(line, "material/thindielectric", "Material \"thindielectric\": a solid dielectric instead");
        if (glm::all(glm::equal(kt, glm::vec3(0.0f)))) {
            // No transmission: only the Fresnel reflection of the surface, a black glossy coat.
            m.type = MaterialType::Plastic;
            m.color = glm::vec3(0.0f);
            m.specular = 1.0f;
            m.shininess = 10000.0f;
            consumed();
            return m;
        }
        m.type = MaterialType::Dielectric;
        const PbrtParam* eta = p.find(type == "glass" ? "index" : "eta");
        if (!eta && type == "glass") eta = p.find("eta");
        m.ior = eta && eta->numbers.size() == 1 ? float(eta->numbers[0]) : 1.5f;
        if (eta && eta->type == "spectrum")
            context.warn(eta->line, "eta/spectrum", "a spectral index of refraction is taken as 1.5");
        if (!(m.ior > 0.0f)) throw PbrtLineError{line, "the index of refraction must be positive"};
        m.roughness = roughnessOf(microfacetAlpha(p, 0.0f, type == "glass"));
    } else if (type == "uber") {
        const PbrtParam* opacity = p.find("opacity");
        if (opacity && opacity->numbers.size() == 3 && opacity->numbers[0] == 0 && opacity->numbers[1] == 0 && opacity->numbers[2] == 0)
            return consumed(), std::nullopt;
        if (opacity) context.warn(line, "uber/opacity", "Material \"uber\": partial opacity is not supported; opaque instead");
        colorSlot(p, "Kd", glm::vec3(0.25f), m, context);
        const glm::vec3 ks = pbrtColor(p, "Ks", glm::vec3(0.25f), context);
        if (mean(ks) > 0.0f) {
            m.type = MaterialType::Plastic;
            m.specular = std::clamp(mean(ks), 0.0f, 1.0f);
            m.shininess = shininessOf(microfacetAlpha(p, 0.1f, true));
        }
        for (const char* unsupported : {"Kr", "Kt", "index"})
            if (const PbrtParam* q = p.find(unsupported))
                context.warn(q->line, std::string("uber/") + unsupported, std::string("Material \"uber\": \"") + unsupported + "\" is not supported; ignored");
    } else {
        context.warn(line, "material/" + type, "Material \"" + type + "\" is not supported; a diffuse material of its color instead");
        if (p.has("Kd")) colorSlot(p, "Kd", glm::vec3(0.5f), m, context);
        else if (p.has("reflectance")) colorSlot(p, "reflectance", glm::vec3(0.5f), m, context);
        else m.color = glm::vec3(0.5f);
        consumed();
    }
    return m;
}

PbrtTexture pbrtTexture(const std::string& type, const std::string& valueType, const PbrtParams& p,
                        const std::filesystem::path& folder, int line, PbrtTextureImages& images, const PbrtWarn& warn) {
    PbrtTexture out;
    static const std::map<std::string, PbrtTexture> kNoTextures;
    const PbrtMaterialContext context{kNoTextures, warn};
    auto constant = [&](const char* name, glm::vec3 fallback) {
        const PbrtParam* q = p.find(name);
        if (q && q->type == "texture") {
            warn(q->line, "texture/nested", "textures of textures are not supported; a grey instead");
            return glm::vec3(0.5f);
        }
        return q ? pbrtColor(p, name, fallback, context) : fallback;
    };
    if (type == "imagemap") {
        const PbrtParam* file = p.find("filename");
        if (!file || file->strings.size() != 1) throw PbrtLineError{line, "Texture \"imagemap\" needs \"string filename\""};
        std::filesystem::path path = file->strings[0];
        if (path.is_relative()) path = folder / path;
        // Filtering and wrapping are pbrt's business; the decoding follows the value type.
        for (const char* ignored : {"filter", "trilinear", "maxanisotropy", "wrap", "gamma", "encoding"}) p.find(ignored);
        const bool srgb = valueType != "float";
        auto& image = images[{path, srgb}];
        if (!image) {
            try {
                image = std::make_shared<const Image>(readImage(path, srgb));
            } catch (const InputError& e) {
                warn(line, "imagemap/unreadable",
                     std::string("Texture \"imagemap\": ") + e.what() + "; unreadable images are a grey (this one and any later)");
                return out;
            }
        }
        Texture texture;
        texture.type = TextureType::Image;
        texture.file = path;
        texture.image = image;
        out.texture = texture;
        for (const auto& [name, identity] : {std::pair{"uscale", 1.0f}, {"vscale", 1.0f}, {"udelta", 0.0f}, {"vdelta", 0.0f}})
            if (p.number(name, identity) != identity)
                warn(line, std::string("imagemap/") + name, std::string("Texture \"imagemap\": \"") + name + "\" is not supported; ignored");
    } else if (type == "constant") {
        out.constant = constant("value", glm::vec3(1.0f));
    } else if (type == "checkerboard") {
        Texture texture;
        texture.type = TextureType::Checker;
        texture.color0 = constant("tex1", glm::vec3(1.0f));
        texture.color1 = constant("tex2", glm::vec3(0.0f));
        texture.scale = p.number("uscale", 1.0f);
        p.number("vscale", 1.0f);
        warn(line, "checkerboard", "Texture \"checkerboard\": a solid checker of the world position instead of one over uv");
        out.texture = texture;
    } else if (type == "fbm" || type == "marble") {
        Texture texture;
        texture.type = type == "fbm" ? TextureType::Fbm : TextureType::Marble;
        texture.octaves = int(std::clamp(p.number("octaves", 8.0f), 1.0f, 16.0f));
        texture.scale = p.number("scale", 1.0f);
        out.texture = texture;
        for (const PbrtParam& q : p.list) q.used = true;
    } else {
        warn(line, "texture/" + type, "Texture \"" + type + "\" is not supported; a grey instead");
        for (const PbrtParam& q : p.list) q.used = true;
    }
    return out;
}

} // namespace wideray
