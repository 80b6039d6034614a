#include "shading/direct_lighting.h"

#include <algorithm>
#include <cmath>

namespace wideray {
namespace {

void addSample(const glm::vec3& position, const glm::vec3& toLight, float distance, const glm::vec3& irradiance,
               float epsilon, std::vector<LightSample>& out, float pdf = 0.0f, int count = 1) {
    LightSample s;
    s.shadowRay.ox = position.x; s.shadowRay.oy = position.y; s.shadowRay.oz = position.z;
    s.shadowRay.dx = toLight.x; s.shadowRay.dy = toLight.y; s.shadowRay.dz = toLight.z;
    s.shadowRay.tnear = epsilon;
    s.shadowRay.tfar = distance - epsilon;
    s.direction = toLight;
    s.distance = distance;
    s.irradiance = irradiance;
    s.pdf = pdf;
    s.count = count;
    out.push_back(s);
}

float lightArea(const Light& light) {
    switch (light.type) {
    case LightType::Quad: return glm::length(glm::cross(light.edgeU, light.edgeV));
    case LightType::Triangle: return 0.5f * glm::length(glm::cross(light.edgeU, light.edgeV));
    default: return 4.0f * float(M_PI) * light.radius * light.radius;
    }
}

/// The density over solid angle of a point sampled uniformly over an area, seen at `distance` under
/// `cosLight`.
float solidAnglePdf(float area, float distance, float cosLight) { return distance * distance / (cosLight * area); }

glm::vec3 uniformSphere(float u1, float u2) {
    float z = 1.0f - 2.0f * u1;
    float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
    float phi = 2.0f * float(M_PI) * u2;
    return {r * std::cos(phi), r * std::sin(phi), z};
}

} // namespace

void sampleLights(const std::vector<Light>& lights, const glm::vec3& position, float epsilon, float time,
                  int areaSampleLimit, SampleRng& rng, std::vector<LightSample>& out) {
    const size_t first = out.size();
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
        case LightType::Triangle:
        case LightType::Sphere: {
            const int n = std::clamp(light.samples, 1, std::max(1, areaSampleLimit));
            for (int i = 0; i < n; ++i) {
                glm::vec2 u = glm::min(stratifiedPoint(i, n, rng), glm::vec2(1.0f));
                glm::vec3 p, lightNormal;
                const float area = lightArea(light);
                if (light.isPlanar()) {
                    // The half of the square beyond the diagonal folds onto the triangle: uniform there too.
                    if (light.type == LightType::Triangle && u.x + u.y > 1.0f) u = glm::vec2(1.0f) - u;
                    p = light.position + u.x * light.edgeU + u.y * light.edgeV;
                    lightNormal = glm::normalize(glm::cross(light.edgeU, light.edgeV));
                } else {
                    lightNormal = uniformSphere(u.x, u.y);
                    p = light.position + light.radius * lightNormal;
                }
                glm::vec3 d = p - position;
                float dist = glm::length(d);
                if (dist <= 2.0f * epsilon) continue;
                glm::vec3 l = d / dist;
                // Quads and triangles emit on the side edge_u x edge_v points to; spheres outward.
                float cosLight = std::max(0.0f, -glm::dot(lightNormal, l));
                if (cosLight <= 0.0f) continue;
                addSample(position, l, dist, power * (cosLight * area / (dist * dist * float(n))), epsilon, out,
                          solidAnglePdf(area, dist, cosLight), n);
            }
            break;
        }
        }
    }
    for (size_t i = first; i < out.size(); ++i) out[i].shadowRay.time = time;
}

void lightCrossings(const std::vector<Light>& lights, const Ray& ray, float tmax, std::vector<LightCrossing>& out) {
    const glm::vec3 o(ray.ox, ray.oy, ray.oz), d(ray.dx, ray.dy, ray.dz);
    for (const Light& light : lights) {
        if (!light.isArea()) continue;
        const int count = std::max(1, light.samples);
        const float area = lightArea(light);
        float t;
        glm::vec3 normal;
        if (light.isPlanar()) {
            const glm::vec3 cross = glm::cross(light.edgeU, light.edgeV);
            const float parallelogram = glm::length(cross);
            normal = cross / parallelogram;
            const float facing = glm::dot(d, normal);
            if (!(facing < 0.0f)) continue;  // parallel, or from behind: they emit on one side
            t = glm::dot(light.position - o, normal) / facing;
            if (!(t > ray.tnear && t < tmax)) continue;
            const glm::vec3 p = o + t * d - light.position;
            // p = s edgeU + r edgeV, solved in the plane (the quad may be a parallelogram).
            const float s = glm::dot(glm::cross(p, light.edgeV), normal) / parallelogram;
            const float r = glm::dot(glm::cross(light.edgeU, p), normal) / parallelogram;
            if (s < 0.0f || s > 1.0f || r < 0.0f || r > 1.0f) continue;
            if (light.type == LightType::Triangle && s + r > 1.0f) continue;
        } else {
            // The near side of the sphere, seen from outside.
            const glm::vec3 oc = o - light.position;
            const float b = glm::dot(oc, d), c = glm::dot(oc, oc) - light.radius * light.radius;
            const float disc = b * b - c;
            if (c <= 0.0f || !(disc > 0.0f)) continue;
            t = -b - std::sqrt(disc);
            if (!(t > ray.tnear && t < tmax)) continue;
            normal = (oc + t * d) / light.radius;
        }
        const float cosLight = -glm::dot(normal, d);
        if (!(cosLight > 0.0f)) continue;
        out.push_back({t, light.color * light.intensity, solidAnglePdf(area, t, cosLight), count});
    }
}

} // namespace wideray
