#pragma once
// The scene's homogeneous fog: extinction exp(-density d) along every segment, and single scattering
// of the lights' light towards the viewer, estimated by ray marching with stratified jittered steps
// and a shadow ray per light at every step (Pharr, Jakob and Humphreys, "Physically Based Rendering",
// 3rd ed., 11.1 and 15.2, with an isotropic phase function). The fog fills the box around the scene's
// objects and lights; rays that leave it travel on without fog.
#include <vector>

#include <glm/glm.hpp>

#include "core/bounds.h"
#include "shading/path_state.h"
#include "core/random.h"
#include "core/scene.h"
#include "shading/direct_lighting.h"

namespace wideray {

class FogMedium {
public:
    /// Steps of the ray march per segment.
    static constexpr int kSteps = 24;

    FogMedium(const Fog& fog, const Bounds3f& region);

    bool present() const { return density_ > 0.0f && !region_.empty(); }

    /// The fraction of light that crosses [0, tmax] of `ray` (unit direction; tmax may be infinite).
    float transmittance(const Ray& ray, float tmax) const;

    /// Appends the shadow samples of the light the fog scatters towards the origin of `ray` from
    /// along [0, tmax], each weighted by `weight` (the path's throughput) and the transmittance to
    /// the origin and to the light. Area lights get one sample per step.
    void addInscattering(const std::vector<Light>& lights, const Ray& ray, float tmax, const glm::vec3& weight,
                         float epsilon, uint32_t pixelX, uint32_t pixelY, SampleRng& rng,
                         std::vector<LightSample>& scratch, std::vector<ShadowSample>& out) const;

private:
    /// The part of [0, tmax] of the ray inside the region; t0 >= t1 when none.
    void clip(const Ray& ray, float tmax, float& t0, float& t1) const;

    float density_;
    glm::vec3 albedo_;
    Bounds3f region_;
};

} // namespace wideray
