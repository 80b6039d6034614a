#include "shading/direct_lighting.h"

#include <algorithm>
#include <cmath>

namespace wideray {
namespace {

void addSample(const glm::vec3& position, const glm::vec3& toLight, float distance, const glm::vec3& irradiance,
               float epsilon, std::vector<LightSample>& out) {
    LightSample s;
    s.shadowRay.ox = position.x; s.shadowRay.oy = position.y; s.shadowRay.oz = position.z;
    s.shadowRay.dx = toLight.x; s.shadowRay.dy = toLight.y; s.shadowRay.dz = toLight.z;
    s.shadowRay.tnear = epsilon;
    s.shadowRay.tfar = distance - epsilon;
    s.direction = toLight;
    s.distance = distance;
    s.irradiance = irradiance;
    out.push_back(s);
}

glm::vec3 uniformSphere(float u1, float u2) {
    float z = 1.0f - 2.0f * u1;
    float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
    float phi = 2.0f * float(M_PI) * u2;
    return {r * std::cos(phi), r * std::sin(phi), z};
}

} // namespace

void sampleLights(const std::vector<Light>& lights, const glm::vec3& position, float epsilon, int areaSampleLimit,
                  SampleRng& rng, std::vector<LightSample>& out) {
    for (const Light& light : lights) {
        const glm::vec3 power = light.color * light.intensity;
        switch (light.type) {
        case LightType::Point: {
            glm::vec3 d = light.position - position;
            float dist = glm::length(d);
            if (dist > 2.0f * epsilon) addSample(position, d / dist, dist, power / (dist * dist), epsilon, out);
            break;
        }
        case LightType::Directional:
            addSample(position, -glm::normalize(light.direction), INFINITY, power, epsilon, out);
            break;
        case LightType::Quad:
        case LightType::Sphere: {
            const int n = std::clamp(light.samples, 1, std::max(1, areaSampleLimit));
            for (int i = 0; i < n; ++i) {
                const glm::vec2 u = glm::min(stratifiedPoint(i, n, rng), glm::vec2(1.0f));
                glm::vec3 p, lightNormal;
                float area;
                if (light.type == LightType::Quad) {
                    p = light.position + u.x * light.edgeU + u.y * light.edgeV;
                    glm::vec3 c = glm::cross(light.edgeU, light.edgeV);
                    area = glm::length(c);
                    lightNormal = c / area;
                } else {
                    lightNormal = uniformSphere(u.x, u.y);
                    p = light.position + light.radius * lightNormal;
                    area = 4.0f * float(M_PI) * light.radius * light.radius;
                }
                glm::vec3 d = p - position;
                float dist = glm::length(d);
                if (dist <= 2.0f * epsilon) continue;
                glm::vec3 l = d / dist;
                // Quads emit on the side edge_u x edge_v points to; spheres outward.
                float cosLight = std::max(0.0f, -glm::dot(lightNormal, l));
                if (cosLight <= 0.0f) continue;
                addSample(position, l, dist, power * (cosLight * area / (dist * dist * float(n))), epsilon, out);
            }
            break;
        }
        }
    }
}

} // namespace wideray
