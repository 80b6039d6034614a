#pragma once
// Absorption inside a homogeneous medium: the Beer-Lambert law, T = exp(-sigma_a d), per RGB channel.
#include <glm/glm.hpp>

#include "simd/isa_namespace.h"

namespace wideray {
inline namespace WIDERAY_ISA {

/// The fraction of light left after travelling `distance` through a medium that absorbs `sigmaA`
/// (per unit length) of each channel.
inline glm::vec3 beerTransmittance(const glm::vec3& sigmaA, float distance) { return glm::exp(-sigmaA * distance); }

} // namespace WIDERAY_ISA
} // namespace wideray
