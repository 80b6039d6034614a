#pragma once
// Light sampling: one shadow ray per point light, directional light and area-light sample, with the
// light each brings if it is not occluded. Surfaces and the fog weigh the samples by their own
// scattering; the renderer resolves all shadow rays of a bounce in one batch.
#include <vector>

#include <glm/glm.hpp>

#include "core/random.h"
#include "core/ray.h"
#include "core/scene.h"

namespace wideray {

/// Light arriving at a point from one light sample, counted only if `shadowRay` is not occluded.
struct LightSample {
    Ray shadowRay;         ///< from the point towards the light, over [epsilon, distance - epsilon]
    glm::vec3 direction;   ///< unit, towards the light
    float distance;        ///< to the sampled point of the light; infinite for directional lights
    glm::vec3 irradiance;  ///< on a surface facing the light, already divided by the light's sample count
};

/// Appends the samples of every light seen from `position`. An area light gets its `samples` shadow
/// rays, stratified over its surface, but at most `areaSampleLimit`. Samples from behind a one-sided
/// light, or from a light closer than 2 `epsilon`, are left out.
void sampleLights(const std::vector<Light>& lights, const glm::vec3& position, float epsilon, int areaSampleLimit,
                  SampleRng& rng, std::vector<LightSample>& out);

} // namespace wideray
