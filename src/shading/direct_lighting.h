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
    float pdf = 0.0f;      ///< area lights: the density of the sample over solid angle; 0 for point and directional lights
    int count = 1;         ///< the samples its light got
};

/// Where a ray crosses the emitting side of an area light: the light's radiance there and the
/// densities with which light sampling would have chosen that direction (for multiple importance
/// sampling). Lights are not surfaces: they emit towards rays that cross them but block nothing.
struct LightCrossing {
    float t;
    glm::vec3 radiance;
    float pdf;  ///< over solid angle, of one light sample
    int count;  ///< the samples sampleLights gives that light at a surface
};

/// Appends the crossings of `ray` (unit direction) with the emitting side of the area lights
/// within (ray.tnear, tmax).
void lightCrossings(const std::vector<Light>& lights, const Ray& ray, float tmax, std::vector<LightCrossing>& out);

/// Appends the samples of every light seen from `position`. An area light gets its `samples` shadow
/// rays, stratified over its surface, but at most `areaSampleLimit`. Samples from behind a one-sided
/// light, or from a light closer than 2 `epsilon`, are left out. The shadow rays are at `time`.
void sampleLights(const std::vector<Light>& lights, const glm::vec3& position, float epsilon, float time,
                  int areaSampleLimit, SampleRng& rng, std::vector<LightSample>& out);

} // namespace wideray
