#include "shading/path_vertex.h"

#include <algorithm>
#include <climits>
#include <cmath>

#include "shading/material_model.h"

namespace wideray {
namespace {

constexpr float kInvPi = 0.318309886f;
/// Scattering events before Russian roulette may end a path.
constexpr int kRouletteDepth = 3;

/// The part of a material that light sampling and direction sampling share at one vertex: diffuse,
/// plastic and rough conductors, each with f(l) cos(theta_l) in closed form and a sampler for it.
struct SampledLobes {
    MaterialType type;
    glm::vec3 normal, toViewer;
    glm::vec3 albedo{0.0f};       ///< diffuse, plastic
    float specular = 0.0f, shininess = 0.0f, specularChance = 0.0f;  ///< plastic
    glm::vec3 mirrored{0.0f};     ///< conductor
    float roughness = 0.0f;
    PolarizedFactor fresnel{};

    /// f(l) cos(theta_l) as s and p factors, and the density with which sample() picks `l`.
    PolarizedFactor evaluate(const glm::vec3& l, float& pdf) const {
        pdf = 0.0f;
        const float cosine = glm::dot(normal, l);
        if (!(cosine > 0.0f)) return {glm::vec3(0.0f), glm::vec3(0.0f)};
        if (type == MaterialType::Conductor) {
            // The glossy lobe is its own density times the Fresnel reflectance at the viewer's angle.
            pdf = glossyPdf(mirrored, roughness, l);
            return {fresnel.s * pdf, fresnel.p * pdf};
        }
        glm::vec3 f = albedo * kInvPi;
        pdf = cosine * kInvPi;
        if (type == MaterialType::Plastic) {
            f += glm::vec3(specular * blinnPhong(normal, l, toViewer, shininess));
            pdf = (1.0f - specularChance) * pdf + specularChance * blinnPhongPdf(normal, toViewer, shininess, l);
        }
        return {f * cosine, f * cosine};
    }

    /// A direction `l` with the weight f cos / pdf; false where the sample is absorbed.
    bool sample(SampleRng& rng, glm::vec3& l, PolarizedFactor& weight, float& pdf) const {
        const float choice = rng.next(), u1 = rng.next(), u2 = rng.next();
        if (type == MaterialType::Conductor) l = glossyDirection(mirrored, roughness, u1, u2);
        else if (type == MaterialType::Plastic && choice < specularChance) l = blinnPhongDirection(normal, toViewer, shininess, u1, u2);
        else l = cosineDirection(normal, u1, u2);
        const PolarizedFactor f = evaluate(l, pdf);
        if (!(pdf > 0.0f)) return false;
        weight = {f.s / pdf, f.p / pdf};
        return true;
    }
};

float maxComponent(const glm::vec3& v) { return std::max({v.x, v.y, v.z}); }

/// A shadow sample per light sample, weighted by the lobes and, for area lights, by the balance
/// heuristic against sampling the lobes.
void sampleDirectLight(const ShadingContext& context, const PathState& path, const SurfacePoint& sp,
                       const SampledLobes& lobes, SampleRng& rng, ScatterOutput& out) {
    out.lightScratch.clear();
    sampleLights(context.scene.lights, sp.position, context.epsilon, path.ray.time, INT_MAX, rng, out.lightScratch);
    for (const LightSample& light : out.lightScratch) {
        float lobePdf;
        const PolarizedFactor f = lobes.evaluate(light.direction, lobePdf);
        const glm::vec3 value = 0.5f * (path.throughputS * f.s + path.throughputP * f.p);
        if (maxComponent(value) <= 0.0f) continue;
        const float weight = light.pdf > 0.0f ? balanceHeuristic(float(light.count) * light.pdf, lobePdf) : 1.0f;
        const float fog = context.fog.transmittance(light.shadowRay, light.distance);
        out.shadows.push_back({light.shadowRay, value * light.irradiance * (weight * fog), path.pixelX, path.pixelY});
    }
}

/// Continues `path` from `position` along `direction` with the event's factor; `scatterPdf` as in
/// PathState. A depolarizing event first averages the s and p throughputs. Russian roulette may end it.
void continuePath(const ShadingContext& context, const PathState& path, const glm::vec3& position,
                  const glm::vec3& direction, const PolarizedFactor& factor, float scatterPdf, const MediumStack& media,
                  SampleRng& rng, ScatterOutput& out, bool depolarize = false) {
    PathState next = path;
    if (depolarize) next.throughputS = next.throughputP = path.throughput();
    next.ray = Ray{position.x, position.y, position.z, direction.x, direction.y, direction.z, context.epsilon, INFINITY,
                   path.ray.time};
    next.depth = path.depth + 1;
    next.scatterPdf = scatterPdf;
    next.media = media;
    next.scaleThroughput(factor, context.scene.render.polarized);
    // A path that carries less than it started with survives with that fraction, so that survivors
    // carry as much as they started with (as pbrt-v4 does): weights never grow beyond 1 through the
    // roulette, and lossless paths (a white furnace) are never cut.
    const float survival = maxComponent(next.throughput());
    if (next.depth >= kRouletteDepth && survival < 1.0f) {
        if (!(rng.next() < survival)) return;
        next.throughputS /= survival;
        next.throughputP /= survival;
    }
    if (maxComponent(next.throughput()) > 0.0f) out.continuations.push_back(next);
}

/// Reflection or refraction, chosen with the probability of its unpolarized Fresnel factor, then
/// spread by the glossy lobe where the material is rough.
void scatterDielectric(const ShadingContext& context, const PathState& path, const SurfacePoint& sp,
                       const glm::vec3& direction, const glm::vec3& normal, SampleRng& rng, ScatterOutput& out) {
    const Material& material = context.scene.materials[sp.material];
    const DielectricCrossing crossing = crossDielectric(context.scene, path.media, sp, direction, normal);
    const FresnelReflectance<float>& r = crossing.reflectance;
    const float reflectChance = crossing.refracted ? r.unpolarized() : 1.0f;
    const bool reflect = rng.next() < reflectChance;
    const float chance = reflect ? reflectChance : 1.0f - reflectChance;
    const PolarizedFactor factor = reflect ? PolarizedFactor{glm::vec3(r.s / chance), glm::vec3(r.p / chance)}
                                           : PolarizedFactor{glm::vec3((1.0f - r.s) / chance), glm::vec3((1.0f - r.p) / chance)};
    glm::vec3 outgoing = reflect ? crossing.reflected : *crossing.refracted;
    const float u1 = rng.next(), u2 = rng.next();
    const float roughness = materialRoughness(material, sp.position, sp.uv);
    if (roughness > 0.0f) {
        outgoing = glossyDirection(outgoing, roughness, u1, u2);
        if ((reflect ? 1.0f : -1.0f) * glm::dot(outgoing, normal) <= 0.0f) return;  // absorbed
    }
    continuePath(context, path, sp.position, outgoing, factor, 0.0f, reflect ? path.media : crossing.beyond, rng, out);
}

} // namespace

void scatterPathVertex(const ShadingContext& context, const PathState& path, const SurfacePoint& sp, SampleRng& rng,
                       ScatterOutput& out) {
    const Material& material = context.scene.materials[sp.material];
    const glm::vec3 direction(path.ray.dx, path.ray.dy, path.ray.dz);
    const glm::vec3 normal = glm::dot(sp.shadingNormal, direction) < 0.0f ? sp.shadingNormal : -sp.shadingNormal;
    const bool lastEvent = path.depth >= context.scene.render.maxDepth;
    const glm::vec3 mirrored = reflectDirection(direction, normal);

    SampledLobes lobes{material.type, normal, -direction};
    switch (material.type) {
    case MaterialType::Diffuse:
        lobes.albedo = materialColor(material, sp);
        break;
    case MaterialType::Plastic:
        lobes.albedo = materialColor(material, sp);
        lobes.specular = material.specular;
        lobes.shininess = material.shininess;
        if (lobes.specular > 0.0f)
            lobes.specularChance = lobes.specular / (lobes.specular + std::max(maxComponent(lobes.albedo), 1e-6f));
        break;
    case MaterialType::Conductor:
        lobes.roughness = materialRoughness(material, sp.position, sp.uv);
        lobes.fresnel = conductorFresnel(material, -glm::dot(direction, normal));
        lobes.mirrored = mirrored;
        if (lobes.roughness > 0.0f) break;
        if (!lastEvent) continuePath(context, path, sp.position, mirrored, lobes.fresnel, 0.0f, path.media, rng, out);
        return;
    case MaterialType::Mirror: {
        const glm::vec3 tint = materialColor(material, sp);
        if (!lastEvent) continuePath(context, path, sp.position, mirrored, {tint, tint}, 0.0f, path.media, rng, out);
        return;
    }
    case MaterialType::Dielectric:
        if (!lastEvent) scatterDielectric(context, path, sp, direction, normal, rng, out);
        return;
    }

    sampleDirectLight(context, path, sp, lobes, rng, out);
    if (lastEvent) return;
    glm::vec3 l;
    PolarizedFactor weight;
    float pdf;
    if (!lobes.sample(rng, l, weight, pdf)) return;
    continuePath(context, path, sp.position, l, weight, pdf, path.media, rng, out,
                 material.type != MaterialType::Conductor);
}

} // namespace wideray
