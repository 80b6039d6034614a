// Material evaluation helpers. Metal constants: RGB values (linear sRGB primaries) of the measured
// spectra shipped with Mitsuba and pbrt-v3 (Palik, "Handbook of Optical Constants of Solids", 1985),
// as tabulated in Tungsten's ComplexIorData.hpp and yocto-gl's conductor_eta.
#include "shading/material_model.h"

#include <algorithm>
#include <cmath>
#include <map>

#include "shading/fresnel.h"
#include "shading/texture.h"

namespace wideray {
namespace {

const std::map<std::string, ComplexIor>& presets() {
    static const std::map<std::string, ComplexIor> table = {
        {"aluminium", {{1.6574599595f, 0.8803689579f, 0.5212287346f}, {9.2238691996f, 6.2695232477f, 4.8370012281f}}},
        {"copper", {{0.2004376970f, 0.9240334304f, 1.1022119527f}, {3.9129485033f, 2.4528477015f, 2.1421879552f}}},
        {"gold", {{0.1431189557f, 0.3749570432f, 1.4424785571f}, {3.9831604247f, 2.3857207478f, 1.6032152899f}}},
        {"silver", {{0.1552646489f, 0.1167232965f, 0.1383806959f}, {4.8283433224f, 3.1222459278f, 2.1469504455f}}},
    };
    return table;
}

/// Two unit vectors completing `n` to an orthonormal basis (Duff et al. 2017, "Building an
/// Orthonormal Basis, Revisited").
void orthonormalBasis(const glm::vec3& n, glm::vec3& b1, glm::vec3& b2) {
    const float sign = std::copysign(1.0f, n.z);
    const float a = -1.0f / (sign + n.z), b = n.x * n.y * a;
    b1 = glm::vec3(1.0f + sign * n.x * n.x * a, sign * b, -sign * n.x);
    b2 = glm::vec3(b, sign + n.y * n.y * a, -n.y);
}

/// The exponent of the glossy lobe for alpha = roughness^2 > 0.
float glossyExponent(float alpha) { return std::max(2.0f / (alpha * alpha) - 2.0f, 0.0f); }

/// A direction about the unit `axis` with density (e + 1) / (2 pi) cos^e(theta).
glm::vec3 cosinePowerDirection(const glm::vec3& axis, float exponent, float u1, float u2) {
    const float cosTheta = std::pow(u1, 1.0f / (exponent + 1.0f));
    const float sinTheta = std::sqrt(std::max(1.0f - cosTheta * cosTheta, 0.0f));
    const float phi = 2.0f * float(M_PI) * u2;
    glm::vec3 b1, b2;
    orthonormalBasis(axis, b1, b2);
    return glm::normalize(sinTheta * (std::cos(phi) * b1 + std::sin(phi) * b2) + cosTheta * axis);
}

float cosinePowerPdf(float exponent, float cosTheta) {
    if (!(cosTheta > 0.0f)) return 0.0f;
    return (exponent + 1.0f) / (2.0f * float(M_PI)) * std::pow(cosTheta, exponent);
}

} // namespace

std::optional<ComplexIor> conductorPreset(const std::string& name) {
    const auto it = presets().find(name);
    if (it == presets().end()) return std::nullopt;
    return it->second;
}

const std::vector<std::string>& conductorPresetNames() {
    static const std::vector<std::string> names = [] {
        std::vector<std::string> all;
        for (const auto& [name, ior] : presets()) all.push_back(name);
        return all;
    }();
    return names;
}

glm::vec3 materialColor(const Material& material, const glm::vec3& position, const glm::vec2& uv) {
    return material.colorTexture ? evaluateColor(*material.colorTexture, position, uv) : material.color;
}

glm::vec3 materialColor(const Material& material, const SurfacePoint& sp) {
    return materialColor(material, sp.position, sp.uv) * sp.vertexColor;
}

float materialRoughness(const Material& material, const glm::vec3& position, const glm::vec2& uv) {
    const float r = material.roughnessTexture ? evaluateScalar(*material.roughnessTexture, position, uv) : material.roughness;
    return std::clamp(r, 0.0f, 1.0f);
}

glm::vec3 conductorReflectance(const glm::vec3& eta, const glm::vec3& k, float cosTheta) {
    glm::vec3 r;
    for (int c = 0; c < 3; ++c) r[c] = fresnelConductor(cosTheta, eta[c], k[c]).unpolarized();
    return r;
}

float blinnPhong(const glm::vec3& normal, const glm::vec3& toLight, const glm::vec3& toViewer, float shininess) {
    const glm::vec3 sum = toLight + toViewer;
    const float length = glm::length(sum);
    if (!(length > 0.0f)) return 0.0f;
    const float cosNH = std::max(glm::dot(normal, sum / length), 0.0f);
    return (shininess + 8.0f) / (8.0f * float(M_PI)) * std::pow(cosNH, shininess);
}

glm::vec3 glossyDirection(const glm::vec3& ideal, float roughness, float u1, float u2) {
    const float alpha = roughness * roughness;
    if (!(alpha > 0.0f)) return ideal;
    return cosinePowerDirection(ideal, glossyExponent(alpha), u1, u2);
}

float glossyPdf(const glm::vec3& ideal, float roughness, const glm::vec3& direction) {
    return cosinePowerPdf(glossyExponent(roughness * roughness), glm::dot(ideal, direction));
}

glm::vec3 cosineDirection(const glm::vec3& n, float u1, float u2) { return cosinePowerDirection(n, 1.0f, u1, u2); }

glm::vec3 blinnPhongDirection(const glm::vec3& normal, const glm::vec3& toViewer, float shininess, float u1, float u2) {
    const glm::vec3 h = cosinePowerDirection(normal, shininess, u1, u2);
    return 2.0f * glm::dot(toViewer, h) * h - toViewer;
}

float blinnPhongPdf(const glm::vec3& normal, const glm::vec3& toViewer, float shininess, const glm::vec3& toLight) {
    const glm::vec3 sum = toLight + toViewer;
    const float length = glm::length(sum);
    if (!(length > 0.0f)) return 0.0f;
    const glm::vec3 h = sum / length;
    const float cosVH = glm::dot(toViewer, h);
    if (!(cosVH > 0.0f)) return 0.0f;
    return cosinePowerPdf(shininess, glm::dot(normal, h)) / (4.0f * cosVH);
}

} // namespace wideray
