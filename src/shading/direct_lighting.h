#pragma once
// Direct illumination of a diffuse surface: one shadow ray per light sample, resolved in a batch.
#include <vector>

#include <glm/glm.hpp>

#include "core/geometry.h"
#include "core/random.h"
#include "core/ray.h"
#include "core/scene.h"

namespace wideray {

/// The light a shadow ray would bring if it is not occluded.
struct ShadowSample {
    Ray ray;
    glm::vec3 contribution;
};

/// Appends the shadow samples of every light for a Lambertian point with the given albedo.
/// `normal` faces the viewer; `epsilon` is the shadow rays' tnear (and light-side margin).
void sampleDirectLighting(const std::vector<Light>& lights, const glm::vec3& position, const glm::vec3& normal,
                          const glm::vec3& albedo, float epsilon, SampleRng& rng,
                          std::vector<ShadowSample>& out);

} // namespace wideray
