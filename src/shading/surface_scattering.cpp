#include "shading/surface_scattering.h"

#include <algorithm>
#include <climits>
#include <cmath>

#include "shading/fresnel.h"
#include "shading/material_model.h"

namespace wideray {
namespace {

constexpr float kInvPi = 0.318309886f;

/// A specular or glossy lobe: its ideal direction, which side of the surface it leaves on (+1 along
/// the normal, -1 through the surface), its weight, and the media its paths travel in.
struct Lobe {
    glm::vec3 ideal;
    float side;
    PolarizedFactor weight;
    MediumStack media;
    uint32_t firstBranch;
};

/// Diffuse and plastic: a shadow sample per light sample, weighted by the BRDF.
void addDirectLight(const ShadingContext& context, const PathState& path, const SurfacePoint& sp,
                    const glm::vec3& normal, const glm::vec3& toViewer, const Material& material, SampleRng& rng,
                    ScatterOutput& out) {
    const glm::vec3 diffuse = materialColor(material, sp) * kInvPi;
    const glm::vec3 weight = path.throughput();
    out.lightScratch.clear();
    sampleLights(context.scene.lights, sp.position, context.epsilon, path.ray.time, INT_MAX, rng, out.lightScratch);
    for (const LightSample& light : out.lightScratch) {
        const float cosine = glm::dot(normal, light.direction);
        if (cosine <= 0.0f) continue;
        glm::vec3 brdf = diffuse;
        if (material.type == MaterialType::Plastic)  // the highlight takes the light's color, not the surface's
            brdf += glm::vec3(material.specular * blinnPhong(normal, light.direction, toViewer, material.shininess));
        const float fog = context.fog.transmittance(light.shadowRay, light.distance);
        out.shadows.push_back(
            {light.shadowRay, weight * brdf * light.irradiance * (cosine * fog), path.pixelX, path.pixelY});
    }
}

/// Continues `path` along a lobe: the ideal direction when smooth, otherwise glossy samples, as many
/// as the material asks for at the first glossy event of a path and one at later ones (so a path
/// branches at most once). Samples that leave on the wrong side of the surface are absorbed.
void followLobe(const ShadingContext& context, const PathState& path, const glm::vec3& position,
                const glm::vec3& normal, const Material& material, float roughness, const Lobe& lobe,
                SampleRng& rng, ScatterOutput& out) {
    const int count = roughness > 0.0f && !path.glossySplit ? std::max(1, material.samples) : 1;
    const PolarizedFactor weight{lobe.weight.s / float(count), lobe.weight.p / float(count)};
    for (int i = 0; i < count; ++i) {
        glm::vec3 direction = lobe.ideal;
        if (roughness > 0.0f) {
            const glm::vec2 u = stratifiedPoint(i, count, rng);
            direction = glossyDirection(lobe.ideal, roughness, u.x, u.y);
            if (lobe.side * glm::dot(direction, normal) <= 0.0f) continue;
        }
        PathState next = path;
        next.ray = Ray{position.x, position.y, position.z, direction.x, direction.y, direction.z, context.epsilon, INFINITY,
                       path.ray.time};
        next.depth = path.depth + 1;
        next.key = pcgHash(path.key + 0x9e3779b9u * (lobe.firstBranch + uint32_t(i) + 1));
        next.glossySplit = path.glossySplit || count > 1;
        next.media = lobe.media;
        next.scaleThroughput(weight, context.scene.render.polarized);
        const glm::vec3 carried = next.throughput();
        if (std::max({carried.x, carried.y, carried.z}) >= context.scene.render.minThroughput)
            out.continuations.push_back(next);
    }
}

/// Fresnel reflection and Snell refraction, both followed.
void scatterDielectric(const ShadingContext& context, const PathState& path, const SurfacePoint& sp,
                       const glm::vec3& direction, const glm::vec3& normal, SampleRng& rng, ScatterOutput& out) {
    const Material& material = context.scene.materials[sp.material];
    const DielectricCrossing crossing = crossDielectric(context.scene, path.media, sp, direction, normal);
    const FresnelReflectance<float>& r = crossing.reflectance;
    const float roughness = materialRoughness(material, sp.position, sp.uv);
    const uint32_t branches = uint32_t(std::max(1, material.samples));
    followLobe(context, path, sp.position, normal, material, roughness,
               {crossing.reflected, 1.0f, {glm::vec3(r.s), glm::vec3(r.p)}, path.media, 0}, rng, out);
    if (crossing.refracted)
        followLobe(context, path, sp.position, normal, material, roughness,
                   {*crossing.refracted, -1.0f, {glm::vec3(1.0f - r.s), glm::vec3(1.0f - r.p)}, crossing.beyond, branches},
                   rng, out);
}

float indexOfRefraction(const SceneDescription& scene, const MediumStack& media) {
    return media.empty() ? 1.0f : scene.materials[media.innermost()].ior;
}

} // namespace

DielectricCrossing crossDielectric(const SceneDescription& scene, const MediumStack& media, const SurfacePoint& sp,
                                   const glm::vec3& direction, const glm::vec3& normal) {
    const Material& material = scene.materials[sp.material];
    const bool entering = glm::dot(direction, sp.geometricNormal) < 0.0f;
    DielectricCrossing c{};
    c.beyond = media;
    float etaI, etaT;
    if (entering) {
        etaI = indexOfRefraction(scene, media);
        etaT = material.ior;
        c.beyond.push(sp.material);
    } else {
        etaI = material.ior;
        c.beyond.remove(sp.material);
        etaT = indexOfRefraction(scene, c.beyond);
    }
    const float eta = etaT / etaI;
    c.reflectance = fresnelDielectric(-glm::dot(direction, normal), eta);
    c.reflected = reflectDirection(direction, normal);
    c.refracted = refractDirection(direction, normal, eta);
    return c;
}

PolarizedFactor conductorFresnel(const Material& material, float cosine) {
    PolarizedFactor fresnel;
    for (int c = 0; c < 3; ++c) {
        const FresnelReflectance<float> r = fresnelConductor(cosine, material.eta[c], material.k[c]);
        fresnel.s[c] = r.s;
        fresnel.p[c] = r.p;
    }
    return fresnel;
}

void scatterAtSurface(const ShadingContext& context, const PathState& path, const SurfacePoint& sp, SampleRng& rng,
                      ScatterOutput& out) {
    const Material& material = context.scene.materials[sp.material];
    const glm::vec3 direction(path.ray.dx, path.ray.dy, path.ray.dz);
    const glm::vec3 normal = glm::dot(sp.shadingNormal, direction) < 0.0f ? sp.shadingNormal : -sp.shadingNormal;
    if (material.type == MaterialType::Diffuse || material.type == MaterialType::Plastic) {
        addDirectLight(context, path, sp, normal, -direction, material, rng, out);
        return;
    }
    if (path.depth >= context.scene.render.maxDepth) return;
    const glm::vec3 mirrored = reflectDirection(direction, normal);
    switch (material.type) {
    case MaterialType::Mirror: {
        const glm::vec3 tint = materialColor(material, sp);
        followLobe(context, path, sp.position, normal, material, 0.0f, {mirrored, 1.0f, {tint, tint}, path.media, 0},
                   rng, out);
        break;
    }
    case MaterialType::Conductor:
        followLobe(context, path, sp.position, normal, material, materialRoughness(material, sp.position, sp.uv),
                   {mirrored, 1.0f, conductorFresnel(material, -glm::dot(direction, normal)), path.media, 0}, rng, out);
        break;
    case MaterialType::Dielectric: scatterDielectric(context, path, sp, direction, normal, rng, out); break;
    case MaterialType::Diffuse:
    case MaterialType::Plastic: break;
    }
}

} // namespace wideray
