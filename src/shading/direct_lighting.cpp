#include "shading/direct_lighting.h"

#include <cmath>

namespace wideray {
namespace {

constexpr float kInvPi = 0.318309886f;

void addSample(const glm::vec3& position, const glm::vec3& toLight, float distance, const glm::vec3& radiance,
               float epsilon, std::vector<ShadowSample>& out) {
    ShadowSample s;
    s.ray.ox = position.x; s.ray.oy = position.y; s.ray.oz = position.z;
    s.ray.dx = toLight.x; s.ray.dy = toLight.y; s.ray.dz = toLight.z;
    s.ray.tnear = epsilon;
    s.ray.tfar = distance - epsilon;
    s.contribution = radiance;
    out.push_back(s);
}

glm::vec3 uniformSphere(float u1, float u2) {
    float z = 1.0f - 2.0f * u1;
    float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
    float phi = 2.0f * float(M_PI) * u2;
    return {r * std::cos(phi), r * std::sin(phi), z};
}

} // namespace

void sampleDirectLighting(const std::vector<Light>& lights, const glm::vec3& position, const glm::vec3& normal,
                          const glm::vec3& albedo, float epsilon, SampleRng& rng,
                          std::vector<ShadowSample>& out) {
    const glm::vec3 brdf = albedo * kInvPi;
    for (const Light& light : lights) {
        const glm::vec3 power = light.color * light.intensity;
        switch (light.type) {
        case LightType::Point: {
            glm::vec3 d = light.position - position;
            float dist = glm::length(d);
            glm::vec3 l = d / dist;
            float cosine = glm::dot(normal, l);
            if (cosine > 0.0f && dist > 2.0f * epsilon)
                addSample(position, l, dist, brdf * power * (cosine / (dist * dist)), epsilon, out);
            break;
        }
        case LightType::Directional: {
            glm::vec3 l = -glm::normalize(light.direction);
            float cosine = glm::dot(normal, l);
            if (cosine > 0.0f) addSample(position, l, INFINITY, brdf * power * cosine, epsilon, out);
            break;
        }
        case LightType::Quad:
        case LightType::Sphere: {
            int n = std::max(1, light.samples);
            int strata = int(std::ceil(std::sqrt(float(n))));
            for (int i = 0; i < n; ++i) {
                float u1 = (float(i % strata) + rng.next()) / float(strata);
                float u2 = (float(i / strata) + rng.next()) / float(strata);
                glm::vec3 p, lightNormal;
                float area;
                if (light.type == LightType::Quad) {
                    p = light.position + u1 * light.edgeU + u2 * light.edgeV;
                    glm::vec3 c = glm::cross(light.edgeU, light.edgeV);
                    area = glm::length(c);
                    lightNormal = c / area;
                } else {
                    lightNormal = uniformSphere(u1 > 1.0f ? 1.0f : u1, u2 > 1.0f ? 1.0f : u2);
                    p = light.position + light.radius * lightNormal;
                    area = 4.0f * float(M_PI) * light.radius * light.radius;
                }
                glm::vec3 d = p - position;
                float dist = glm::length(d);
                if (dist <= 2.0f * epsilon) continue;
                glm::vec3 l = d / dist;
                float cosSurface = glm::dot(normal, l);
                float cosLight = std::fabs(glm::dot(lightNormal, l));  // quads emit on both faces
                if (light.type == LightType::Sphere) cosLight = std::max(0.0f, -glm::dot(lightNormal, l));
                if (cosSurface <= 0.0f || cosLight <= 0.0f) continue;
                float geometry = cosSurface * cosLight * area / (dist * dist * float(n));
                addSample(position, l, dist, brdf * power * geometry, epsilon, out);
            }
            break;
        }
        }
    }
}

} // namespace wideray
