// Improved Perlin noise (Perlin 2002, "Improving Noise"), transcribed from the reference Java
// implementation: the fixed permutation, the quintic fade 6t^5 - 15t^4 + 10t^3, and gradients along
// the 12 edges of a cube (four of them repeated to fill 16 hash values).
#include "shading/perlin_noise.h"

#include <array>
#include <cmath>
#include <cstdint>

namespace wideray {
namespace {

constexpr std::array<uint8_t, 256> kPermutation = {
    151, 160, 137, 91,  90,  15,  131, 13,  201, 95,  96,  53,  194, 233, 7,   225, 140, 36,  103, 30,  69,  142,
    8,   99,  37,  240, 21,  10,  23,  190, 6,   148, 247, 120, 234, 75,  0,   26,  197, 62,  94,  252, 219, 203,
    117, 35,  11,  32,  57,  177, 33,  88,  237, 149, 56,  87,  174, 20,  125, 136, 171, 168, 68,  175, 74,  165,
    71,  134, 139, 48,  27,  166, 77,  146, 158, 231, 83,  111, 229, 122, 60,  211, 133, 230, 220, 105, 92,  41,
    55,  46,  245, 40,  244, 102, 143, 54,  65,  25,  63,  161, 1,   216, 80,  73,  209, 76,  132, 187, 208, 89,
    18,  169, 200, 196, 135, 130, 116, 188, 159, 86,  164, 100, 109, 198, 173, 186, 3,   64,  52,  217, 226, 250,
    124, 123, 5,   202, 38,  147, 118, 126, 255, 82,  85,  212, 207, 206, 59,  227, 47,  16,  58,  17,  182, 189,
    28,  42,  223, 183, 170, 213, 119, 248, 152, 2,   44,  154, 163, 70,  221, 153, 101, 155, 167, 43,  172, 9,
    129, 22,  39,  253, 19,  98,  108, 110, 79,  113, 224, 232, 178, 185, 112, 104, 218, 246, 97,  228, 251, 34,
    242, 193, 238, 210, 144, 12,  191, 179, 162, 241, 81,  51,  145, 235, 249, 14,  239, 107, 49,  192, 214, 31,
    181, 199, 106, 157, 184, 84,  204, 176, 115, 121, 50,  45,  127, 4,   150, 254, 138, 236, 205, 93,  222, 114,
    67,  29,  24,  72,  243, 141, 128, 195, 78,  66,  215, 61,  156, 180};

/// The permutation for lattice coordinates taken modulo 256.
int hash(int i) { return kPermutation[i & 255]; }

float fade(float t) { return t * t * t * (t * (t * 6.0f - 15.0f) + 10.0f); }

float lerp(float t, float a, float b) { return a + t * (b - a); }

/// The dot product of (x, y, z) with the gradient that the low 4 bits of `h` pick.
float gradient(int h, float x, float y, float z) {
    h &= 15;
    const float u = h < 8 ? x : y;
    const float v = h < 4 ? y : (h == 12 || h == 14 ? x : z);
    return ((h & 1) == 0 ? u : -u) + ((h & 2) == 0 ? v : -v);
}

} // namespace

float perlinNoise(const glm::vec3& p) {
    const glm::vec3 cell = glm::floor(p);
    const int X = int(cell.x) & 255, Y = int(cell.y) & 255, Z = int(cell.z) & 255;
    const float x = p.x - cell.x, y = p.y - cell.y, z = p.z - cell.z;
    const float u = fade(x), v = fade(y), w = fade(z);
    const int A = hash(X) + Y, AA = hash(A) + Z, AB = hash(A + 1) + Z;
    const int B = hash(X + 1) + Y, BA = hash(B) + Z, BB = hash(B + 1) + Z;
    return lerp(w,
                lerp(v, lerp(u, gradient(hash(AA), x, y, z), gradient(hash(BA), x - 1, y, z)),
                     lerp(u, gradient(hash(AB), x, y - 1, z), gradient(hash(BB), x - 1, y - 1, z))),
                lerp(v, lerp(u, gradient(hash(AA + 1), x, y, z - 1), gradient(hash(BA + 1), x - 1, y, z - 1)),
                     lerp(u, gradient(hash(AB + 1), x, y - 1, z - 1), gradient(hash(BB + 1), x - 1, y - 1, z - 1))));
}

float fbm(const glm::vec3& p, int octaves) {
    float sum = 0.0f, frequency = 1.0f;
    for (int i = 0; i < octaves; ++i, frequency *= 2.0f) sum += perlinNoise(frequency * p) / frequency;
    return sum;
}

float turbulence(const glm::vec3& p, int octaves) {
    float sum = 0.0f, frequency = 1.0f;
    for (int i = 0; i < octaves; ++i, frequency *= 2.0f) sum += std::abs(perlinNoise(frequency * p)) / frequency;
    return sum;
}

float marble(const glm::vec3& p, int octaves) { return std::sin(p.x + 5.0f * turbulence(p, octaves)); }

} // namespace wideray
