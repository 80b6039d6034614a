#pragma once
// What the renderer needs to shade the scene's materials (core/scene.h): textured inputs, measured
// metals, the plastic highlight and the glossy lobe.
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "core/geometry.h"
#include "core/scene.h"

namespace wideray {

/// A complex index of refraction eta + ik per RGB channel.
struct ComplexIor {
    glm::vec3 eta, k;
};

/// The measured metals "aluminium", "copper", "gold", "silver"; none for other names.
std::optional<ComplexIor> conductorPreset(const std::string& name);
const std::vector<std::string>& conductorPresetNames();

/// The material's color (diffuse albedo, mirror reflectance) at a surface point.
glm::vec3 materialColor(const Material& material, const glm::vec3& position, const glm::vec2& uv);
/// The same at a surface point, tinted by the mesh's vertex color there.
glm::vec3 materialColor(const Material& material, const SurfacePoint& sp);

/// The material's roughness at a surface point, clamped to [0, 1].
float materialRoughness(const Material& material, const glm::vec3& position, const glm::vec2& uv);

/// Unpolarized Fresnel reflectance of a conductor per RGB channel at cos(theta) = `cosTheta`.
glm::vec3 conductorReflectance(const glm::vec3& eta, const glm::vec3& k, float cosTheta);

/// The plastic highlight: energy-normalized Blinn-Phong, (s + 8) / (8 pi) (n.h)^s (Akenine-Moller et
/// al., "Real-Time Rendering", 3rd ed., 7.6). The radiance towards the viewer is
/// material.specular * blinnPhong(...) * light radiance * max(n.l, 0), in the light's color.
/// All vectors are unit length and point away from the surface.
float blinnPhong(const glm::vec3& normal, const glm::vec3& toLight, const glm::vec3& toViewer, float shininess);

/// A direction of the glossy lobe around the ideal (mirror or refracted) unit direction `ideal`:
/// `ideal` itself for roughness 0, spreading to a cosine-power lobe of exponent 2 / alpha^2 - 2 with
/// alpha = roughness^2 (Walter et al. 2007, "Microfacet Models for Refraction through Rough
/// Surfaces", eq. 30; Burley 2012 for alpha = roughness^2). u1, u2 are uniform in [0, 1). The result
/// may point below the surface; the caller treats such a sample as absorbed.
glm::vec3 glossyDirection(const glm::vec3& ideal, float roughness, float u1, float u2);

/// The density over solid angle with which glossyDirection(ideal, roughness > 0, ...) picks `direction`.
float glossyPdf(const glm::vec3& ideal, float roughness, const glm::vec3& direction);

/// A cosine-weighted direction about the unit normal `n` (density cos(theta) / pi); u1, u2 in [0, 1).
glm::vec3 cosineDirection(const glm::vec3& n, float u1, float u2);

/// A direction sampled for the plastic highlight: a half vector h drawn with density proportional to
/// (n.h)^shininess, reflected about it. It may point below the surface.
glm::vec3 blinnPhongDirection(const glm::vec3& normal, const glm::vec3& toViewer, float shininess, float u1, float u2);

/// The density over solid angle with which blinnPhongDirection picks `toLight`.
float blinnPhongPdf(const glm::vec3& normal, const glm::vec3& toViewer, float shininess, const glm::vec3& toLight);

} // namespace wideray
