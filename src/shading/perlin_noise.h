#pragma once
// Solid noise: Ken Perlin's improved noise (Perlin 2002, "Improving Noise", SIGGRAPH) and the sums
// of octaves built on it (Perlin 1985, "An Image Synthesizer": fbm, turbulence, marble).
#include <glm/glm.hpp>

namespace wideray {

/// Improved Perlin noise at `p`: smooth, zero at every integer lattice point, within
/// +-kPerlinNoiseBound, and the same on every machine (a fixed permutation table, no random state).
float perlinNoise(const glm::vec3& p);

/// A bound of |perlinNoise|. The noise is mostly within [-1, 1] but slightly exceeds 1 where the
/// corner gradients line up: a search of 262144 lattice cells found 1.0288, near (167.36, 55.49, 5.48).
inline constexpr float kPerlinNoiseBound = 1.04f;

/// Fractional Brownian motion: the sum over `octaves` of noise(f p) / f for f = 1, 2, 4, ...
float fbm(const glm::vec3& p, int octaves);

/// Like fbm but summing |noise|, which gives the creases of flames and veins; >= 0.
float turbulence(const glm::vec3& p, int octaves);

/// Marble veins: sin(p.x + 5 turbulence(p)), in [-1, 1].
float marble(const glm::vec3& p, int octaves);

} // namespace wideray
