#pragma once
// What happens where a path meets a surface, per material (core/scene.h), Whitted style (Whitted
// 1980, "An Improved Illumination Model for Shaded Display"; Cook, Porter and Carpenter 1984,
// "Distributed Ray Tracing", for the glossy lobes): diffuse and plastic surfaces take direct light
// only and end the path; mirrors, conductors and dielectrics continue it along their specular (or
// glossy) directions, dielectrics splitting it into a reflected and a refracted path weighted by
// Fresnel. No Russian roulette: paths end at the maximum depth or when they carry too little.
//
// Polarization: in polarized mode the s and p throughputs are multiplied by their own Fresnel
// reflectances (or transmittances) and averaged only when light is added, instead of multiplying by
// the average at every event. This assumes the s and p axes stay aligned from one event to the
// next, i.e. that the planes of incidence along a path coincide (exact for paths in one plane, such
// as a beam between parallel plates, approximate otherwise); it ignores the rotation between
// successive frames that a full Mueller-matrix treatment would carry.
#include <optional>
#include <vector>

#include "core/geometry.h"
#include "shading/path_state.h"
#include "core/random.h"
#include "core/scene.h"
#include "shading/direct_lighting.h"
#include "shading/fog_medium.h"
#include "shading/fresnel.h"

namespace wideray {

/// The scene-wide inputs of shading.
struct ShadingContext {
    const SceneDescription& scene;
    const FogMedium& fog;
    float epsilon;  ///< offset of new rays from the surface
};

/// Where a bounce's work goes: shadow rays for the batch, continuing paths for the next bounce.
struct ScatterOutput {
    std::vector<ShadowSample>& shadows;
    std::vector<PathState>& continuations;
    std::vector<LightSample>& lightScratch;
};

/// What a path meets at the surface of a dielectric: entering and leaving are told by the side of the
/// geometric normal it arrives from; indices are relative to the medium it is in.
struct DielectricCrossing {
    MediumStack beyond;  ///< the media of the refracted path
    FresnelReflectance<float> reflectance;
    glm::vec3 reflected;
    std::optional<glm::vec3> refracted;  ///< none past the critical angle
};

/// The crossing for a path inside `media` arriving along `direction` at `sp`, with `normal` the
/// shading normal turned against `direction`.
DielectricCrossing crossDielectric(const SceneDescription& scene, const MediumStack& media, const SurfacePoint& sp,
                                   const glm::vec3& direction, const glm::vec3& normal);

/// The s and p reflectances of a conductor at cos(theta) = `cosine`, per channel.
PolarizedFactor conductorFresnel(const Material& material, float cosine);

/// Shades the surface `sp` that `path` (its ray of unit direction) has reached, its throughput
/// already including the segment's attenuation.
void scatterAtSurface(const ShadingContext& context, const PathState& path, const SurfacePoint& sp, SampleRng& rng,
                      ScatterOutput& out);

} // namespace wideray
