#pragma once
// Fresnel reflectance of smooth dielectric and conductor boundaries, and the mirror and Snell
// directions. The reflectances are templated on the float type (float or simd::vfloat<W>) and use
// selects instead of branches, so the scalar and the packet shaders share one implementation.
//
// Dielectric: the Fresnel equations (Hecht, "Optics", 5th ed., 4.6). Conductor: the exact closed
// form for a complex index n + ik (Pharr, Jakob and Humphreys, "Physically Based Rendering", 3rd ed.,
// 8.2.1, FrConductor), kept split into its s- and p-polarized parts.
#include <optional>

#include <glm/glm.hpp>

#include "simd/math.h"
#include "simd/simd.h"

namespace wideray {
inline namespace WIDERAY_ISA {

/// Reflectance for light polarized perpendicular (s) and parallel (p) to the plane of incidence.
template <class F>
struct FresnelReflectance {
    F s, p;
    /// Reflectance for unpolarized light.
    F unpolarized() const { return (s + p) * F(0.5f); }
};

/// Reflectance of a smooth boundary between two dielectrics, for light arriving from the side of
/// index n_i at cos(theta_i) = `cosThetaI` (clamped to [0, 1]); `eta` = n_t / n_i. Past the critical
/// angle (total internal reflection) both parts are 1. The transmitted fraction is 1 - reflectance.
template <class F>
FresnelReflectance<F> fresnelDielectric(F cosThetaI, F eta) {
    const F one(1.0f);
    const F cosI = simd::clamp(cosThetaI, F(0.0f), one);
    const F sin2T = (one - cosI * cosI) / (eta * eta);
    const auto totalInternalReflection = sin2T >= one;
    const F cosT = simd::sqrt(simd::max(one - sin2T, F(0.0f)));
    const F rs = (cosI - eta * cosT) / (cosI + eta * cosT);
    const F rp = (eta * cosI - cosT) / (eta * cosI + cosT);
    return {simd::select(totalInternalReflection, one, rs * rs), simd::select(totalInternalReflection, one, rp * rp)};
}

/// Reflectance of a smooth conductor with complex index of refraction `eta` + i `k` (relative to the
/// outside medium), for light arriving at cos(theta_i) = `cosThetaI` (clamped to [0, 1]). Exact.
template <class F>
FresnelReflectance<F> fresnelConductor(F cosThetaI, F eta, F k) {
    const F one(1.0f), two(2.0f), half(0.5f);
    const F cosI = simd::clamp(cosThetaI, F(0.0f), one);
    const F cos2 = cosI * cosI, sin2 = one - cos2;
    const F eta2 = eta * eta, k2 = k * k;
    // a^2 + b^2 = |n_c^2 - sin^2|, with a = Re sqrt(n_c^2 - sin^2) (n_c = eta + ik).
    const F t0 = eta2 - k2 - sin2;
    const F a2PlusB2 = simd::sqrt(t0 * t0 + F(4.0f) * eta2 * k2);
    const F a = simd::sqrt(simd::max(half * (a2PlusB2 + t0), F(0.0f)));
    const F t1 = a2PlusB2 + cos2, t2 = two * cosI * a;
    const F rs = (t1 - t2) / (t1 + t2);
    const F t3 = cos2 * a2PlusB2 + sin2 * sin2, t4 = t2 * sin2;
    return {rs, rs * (t3 - t4) / (t3 + t4)};
}

/// The mirror image of `direction` (travelling towards the surface) about the unit `normal`.
inline glm::vec3 reflectDirection(const glm::vec3& direction, const glm::vec3& normal) {
    return direction - 2.0f * glm::dot(direction, normal) * normal;
}

/// The direction refracted by Snell's law, for a unit `direction` travelling towards a surface
/// whose unit `normal` faces against it; `eta` = n_t / n_i. None on total internal reflection.
inline std::optional<glm::vec3> refractDirection(const glm::vec3& direction, const glm::vec3& normal, float eta) {
    const float cosI = -glm::dot(direction, normal);
    const float sin2T = (1.0f - cosI * cosI) / (eta * eta);
    if (sin2T >= 1.0f) return std::nullopt;
    const float cosT = std::sqrt(1.0f - sin2T);
    return direction / eta + (cosI / eta - cosT) * normal;
}

} // namespace WIDERAY_ISA
} // namespace wideray
