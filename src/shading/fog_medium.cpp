#include "shading/fog_medium.h"

#include <cmath>

namespace wideray {

FogMedium::FogMedium(const Fog& fog, const Bounds3f& region) : density_(fog.density), albedo_(fog.color), region_(region) {}

void FogMedium::clip(const Ray& ray, float tmax, float& t0, float& t1) const {
    const float o[3] = {ray.ox, ray.oy, ray.oz}, d[3] = {ray.dx, ray.dy, ray.dz};
    t0 = 0.0f;
    t1 = tmax;
    for (int a = 0; a < 3; ++a) {
        if (d[a] == 0.0f) {
            if (o[a] < region_.lower[a] || o[a] > region_.upper[a]) t1 = -1.0f;
            continue;
        }
        float near = (region_.lower[a] - o[a]) / d[a], far = (region_.upper[a] - o[a]) / d[a];
        if (near > far) std::swap(near, far);
        t0 = std::max(t0, near);
        t1 = std::min(t1, far);
    }
}

float FogMedium::transmittance(const Ray& ray, float tmax) const {
    if (!present()) return 1.0f;
    float t0, t1;
    clip(ray, tmax, t0, t1);
    return t1 > t0 ? std::exp(-density_ * (t1 - t0)) : 1.0f;
}

void FogMedium::addInscattering(const std::vector<Light>& lights, const Ray& ray, float tmax, const glm::vec3& weight,
                                float epsilon, uint32_t pixelX, uint32_t pixelY, SampleRng& rng,
                                std::vector<LightSample>& scratch, std::vector<ShadowSample>& out) const {
    if (!present()) return;
    float t0, t1;
    clip(ray, tmax, t0, t1);
    if (!(t1 > t0)) return;
    const float step = (t1 - t0) / float(kSteps);
    constexpr float kIsotropicPhase = 0.25f / float(M_PI);
    const glm::vec3 scattering = weight * albedo_ * (density_ * kIsotropicPhase * step);
    const glm::vec3 origin(ray.ox, ray.oy, ray.oz), direction(ray.dx, ray.dy, ray.dz);
    for (int i = 0; i < kSteps; ++i) {
        const float t = t0 + (float(i) + rng.next()) * step;
        const glm::vec3 point = origin + t * direction;
        const float toViewer = std::exp(-density_ * (t - t0));
        scratch.clear();
        sampleLights(lights, point, epsilon, ray.time, 1, rng, scratch);
        for (const LightSample& light : scratch) {
            const float toLight = transmittance(light.shadowRay, light.distance);
            out.push_back({light.shadowRay, scattering * light.irradiance * (toViewer * toLight), pixelX, pixelY});
        }
    }
}

} // namespace wideray
