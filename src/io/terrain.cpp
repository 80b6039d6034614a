#include "io/terrain.h"

#include <algorithm>
#include <cmath>

#include "shading/perlin_noise.h"

namespace wideray {

std::vector<float> ridgedMultifractalHeights(const TerrainParameters& p) {
    const int n = p.resolution + 1;
    std::vector<float> heights(size_t(n) * size_t(n));
    // The seed moves the domain by a lattice-free offset, so that seeds give unrelated terrains.
    // Modulo the noise's period (256), in double, so that any seed keeps full float precision.
    const auto wrap = [&](double f, double add) { return float(std::fmod(double(p.seed) * f, 256.0) + add); };
    const glm::vec3 shift(wrap(17.31, 0.0), wrap(5.77, 0.5), wrap(11.13, 0.0));
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            glm::vec3 q(-1.0f + 2.0f * float(i) / float(p.resolution), 0.0f, -1.0f + 2.0f * float(j) / float(p.resolution));
            q = q * p.frequency + shift;
            float signal = p.offset - std::fabs(perlinNoise(q));
            signal *= signal;
            float result = signal, weight = 1.0f, scale = 1.0f;
            for (int o = 1; o < p.octaves; ++o) {
                q *= p.lacunarity;
                scale /= std::pow(p.lacunarity, p.roughness);
                weight = std::clamp(signal * p.gain, 0.0f, 1.0f);
                signal = p.offset - std::fabs(perlinNoise(q));
                signal *= signal * weight;
                result += signal * scale;
            }
            heights[size_t(j) * size_t(n) + size_t(i)] = result;
        }
    const auto [lo, hi] = std::minmax_element(heights.begin(), heights.end());
    const float low = *lo, range = *hi - *lo;
    for (float& h : heights) h = range > 0.0f ? (h - low) / range * p.height : 0.0f;
    return heights;
}

TriangleMesh heightFieldMesh(const std::vector<float>& heights, int resolution) {
    const int n = resolution + 1;
    TriangleMesh mesh;
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i)
            mesh.positions.push_back({-1.0f + 2.0f * float(i) / float(resolution), heights[size_t(j) * size_t(n) + size_t(i)],
                                      -1.0f + 2.0f * float(j) / float(resolution)});
    for (int j = 0; j < resolution; ++j)
        for (int i = 0; i < resolution; ++i) {
            const uint32_t a = uint32_t(j * n + i), b = a + 1, c = a + uint32_t(n), d = c + 1;
            // Counter-clockwise seen from above (+y).
            mesh.triangles.push_back({a, d, b});
            mesh.triangles.push_back({a, c, d});
        }
    return mesh;
}

} // namespace wideray
