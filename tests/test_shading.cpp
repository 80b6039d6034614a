// The shading library: Fresnel (against closed forms computed here independently), Beer's law,
// Perlin noise, textures and the material helpers.
#include <cmath>
#include <complex>
#include <cstring>
#include <memory>

#include <gtest/gtest.h>

#include "core/random.h"
#include "shading/beer.h"
#include "shading/fresnel.h"
#include "shading/material_model.h"
#include "shading/perlin_noise.h"
#include "shading/texture.h"

namespace wideray {
namespace {

constexpr double kPi = 3.14159265358979323846;

double radians(double degrees) { return degrees * kPi / 180.0; }

// ---- dielectric Fresnel

TEST(Fresnel, NormalIncidenceIsSquaredIndexContrast) {
    for (const auto& [n1, n2] : {std::pair{1.0f, 1.5f}, {1.5f, 1.0f}, {1.0f, 2.4f}, {1.33f, 1.5f}}) {
        const FresnelReflectance<float> r = fresnelDielectric(1.0f, n2 / n1);
        const float expected = ((n1 - n2) / (n1 + n2)) * ((n1 - n2) / (n1 + n2));
        EXPECT_NEAR(r.s, expected, 1e-6f) << n1 << " -> " << n2;
        EXPECT_NEAR(r.p, expected, 1e-6f) << n1 << " -> " << n2;
        EXPECT_NEAR(r.unpolarized(), expected, 1e-6f) << n1 << " -> " << n2;
    }
}

TEST(Fresnel, ParallelReflectanceVanishesAtBrewstersAngle) {
    for (const float eta : {1.5f, 1.33f, 2.4f, 1.0f / 1.5f}) {
        const float brewster = std::atan(eta);
        const FresnelReflectance<float> r = fresnelDielectric(std::cos(brewster), eta);
        EXPECT_NEAR(r.p, 0.0f, 1e-6f) << eta;
        EXPECT_GT(r.s, 0.01f) << eta;
    }
}

TEST(Fresnel, TotalInternalReflectionPastTheCriticalAngle) {
    const float eta = 1.0f / 1.5f;  // glass to air
    const double critical = std::asin(double(eta));
    for (double extra : {1e-3, 0.01, 0.1, 0.5}) {
        const double theta = std::min(critical + extra, kPi / 2);
        const FresnelReflectance<float> r = fresnelDielectric(float(std::cos(theta)), eta);
        EXPECT_EQ(r.s, 1.0f) << theta;
        EXPECT_EQ(r.p, 1.0f) << theta;
    }
    const FresnelReflectance<float> below = fresnelDielectric(float(std::cos(critical - 0.01)), eta);
    EXPECT_LT(below.unpolarized(), 1.0f);
    EXPECT_EQ(fresnelDielectric(0.0f, 1.5f).unpolarized(), 1.0f);  // grazing from outside
}

TEST(Fresnel, ReflectanceAndTransmittanceSumToOne) {
    for (const double eta : {1.5, 1.33, 2.4, 1.0 / 1.5, 1.0 / 1.33}) {
        for (double degrees = 0.0; degrees < 90.0; degrees += 2.5) {
            const double cosI = std::cos(radians(degrees));
            const double sin2T = (1.0 - cosI * cosI) / (eta * eta);
            if (sin2T >= 1.0) continue;
            const double cosT = std::sqrt(1.0 - sin2T);
            // Transmission amplitudes and the power ratio (eta cos_t) / cos_i of the refracted beam.
            const double ts = 2.0 * cosI / (cosI + eta * cosT), tp = 2.0 * cosI / (eta * cosI + cosT);
            const double beam = eta * cosT / cosI;
            const FresnelReflectance<float> r = fresnelDielectric(float(cosI), float(eta));
            EXPECT_NEAR(r.s + beam * ts * ts, 1.0, 1e-5) << eta << " at " << degrees;
            EXPECT_NEAR(r.p + beam * tp * tp, 1.0, 1e-5) << eta << " at " << degrees;
        }
    }
}

// ---- conductor Fresnel

/// Rs and Rp for a complex index, straight from the Fresnel equations and complex Snell's law.
std::pair<double, double> complexFresnel(double cosI, std::complex<double> n) {
    const double sin2I = 1.0 - cosI * cosI;
    const std::complex<double> cosT = std::sqrt(1.0 - sin2I / (n * n));
    const std::complex<double> rs = (cosI - n * cosT) / (cosI + n * cosT);
    const std::complex<double> rp = (n * cosI - cosT) / (n * cosI + cosT);
    return {std::norm(rs), std::norm(rp)};
}

TEST(Fresnel, ConductorMatchesComplexFresnelEquations) {
    for (const char* metal : {"gold", "copper", "silver", "aluminium"}) {
        const ComplexIor ior = *conductorPreset(metal);
        for (const double degrees : {0.0, 60.0, 30.0, 80.0, 89.0}) {
            const double cosI = std::cos(radians(degrees));
            for (int c = 0; c < 3; ++c) {
                const auto [rs, rp] = complexFresnel(cosI, {double(ior.eta[c]), double(ior.k[c])});
                const FresnelReflectance<float> r = fresnelConductor(float(cosI), ior.eta[c], ior.k[c]);
                EXPECT_NEAR(r.s, rs, 1e-5) << metal << " channel " << c << " at " << degrees;
                EXPECT_NEAR(r.p, rp, 1e-5) << metal << " channel " << c << " at " << degrees;
                EXPECT_NEAR(r.unpolarized(), 0.5 * (rs + rp), 1e-5) << metal << " channel " << c << " at " << degrees;
            }
        }
    }
}

TEST(Fresnel, ConductorReflectanceOfGoldAndCopperAtNormalIncidence) {
    // |(n - 1 + ik) / (n + 1 + ik)|^2 at normal incidence: gold and copper reflect red most.
    for (const char* metal : {"gold", "copper"}) {
        const ComplexIor ior = *conductorPreset(metal);
        const glm::vec3 r = conductorReflectance(ior.eta, ior.k, 1.0f);
        for (int c = 0; c < 3; ++c) {
            const double n = ior.eta[c], k = ior.k[c];
            EXPECT_NEAR(r[c], ((n - 1) * (n - 1) + k * k) / ((n + 1) * (n + 1) + k * k), 1e-5) << metal << c;
        }
        EXPECT_GT(r.x, r.z) << metal;
    }
    EXPECT_EQ(conductorReflectance(glm::vec3(1.5f), glm::vec3(3.0f), 0.0f), glm::vec3(1.0f));  // grazing
}

// ---- scalar and packet agree

TEST(Fresnel, PacketAndScalarGiveIdenticalResults) {
    SampleRng rng(1, 2, 3);
    for (int round = 0; round < 1000; ++round) {
        alignas(16) float cosI[4], eta[4], k[4];
        for (int lane = 0; lane < 4; ++lane) {
            cosI[lane] = rng.next() * 1.2f - 0.1f;  // also outside [0, 1], where both clamp
            eta[lane] = 0.3f + 2.5f * rng.next();   // below 1 reaches total internal reflection
            k[lane] = 5.0f * rng.next();
        }
        const auto dielectric = fresnelDielectric(simd::vfloat4::load(cosI), simd::vfloat4::load(eta));
        const auto conductor = fresnelConductor(simd::vfloat4::load(cosI), simd::vfloat4::load(eta), simd::vfloat4::load(k));
        alignas(16) float ds[4], dp[4], cs[4], cp[4];
        dielectric.s.store(ds);
        dielectric.p.store(dp);
        conductor.s.store(cs);
        conductor.p.store(cp);
        for (int lane = 0; lane < 4; ++lane) {
            const auto d = fresnelDielectric(cosI[lane], eta[lane]);
            const auto c = fresnelConductor(cosI[lane], eta[lane], k[lane]);
            EXPECT_EQ(std::memcmp(&ds[lane], &d.s, 4), 0) << ds[lane] << " " << d.s;
            EXPECT_EQ(std::memcmp(&dp[lane], &d.p, 4), 0) << dp[lane] << " " << d.p;
            EXPECT_EQ(std::memcmp(&cs[lane], &c.s, 4), 0) << cs[lane] << " " << c.s;
            EXPECT_EQ(std::memcmp(&cp[lane], &c.p, 4), 0) << cp[lane] << " " << c.p;
        }
    }
}

// ---- directions

TEST(Directions, ReflectionAndSnellRefraction) {
    const glm::vec3 normal(0.0f, 1.0f, 0.0f);
    const float theta = float(radians(40.0));
    const glm::vec3 in(std::sin(theta), -std::cos(theta), 0.0f);
    const glm::vec3 mirrored = reflectDirection(in, normal);
    EXPECT_NEAR(mirrored.x, in.x, 1e-6f);
    EXPECT_NEAR(mirrored.y, -in.y, 1e-6f);

    const float eta = 1.5f;
    const std::optional<glm::vec3> out = refractDirection(in, normal, eta);
    ASSERT_TRUE(out);
    EXPECT_NEAR(glm::length(*out), 1.0f, 1e-6f);
    EXPECT_NEAR(out->x * eta, in.x, 1e-6f);  // sin_t = sin_i / eta
    EXPECT_LT(out->y, 0.0f);

    const glm::vec3 steep(std::sin(1.2f), -std::cos(1.2f), 0.0f);
    EXPECT_FALSE(refractDirection(steep, normal, 1.0f / 1.5f));  // 68.8 degrees > critical 41.8
}

// ---- Beer

TEST(Beer, TransmittanceIsExponentialInDistance) {
    const glm::vec3 sigma(0.5f, 1.0f, 2.0f);
    const glm::vec3 t = beerTransmittance(sigma, 2.0f);
    EXPECT_NEAR(t.x, std::exp(-1.0f), 1e-6f);
    EXPECT_NEAR(t.y, std::exp(-2.0f), 1e-6f);
    EXPECT_NEAR(t.z, std::exp(-4.0f), 1e-6f);
    EXPECT_EQ(beerTransmittance(sigma, 0.0f), glm::vec3(1.0f));
    EXPECT_EQ(beerTransmittance(glm::vec3(0.0f), 100.0f), glm::vec3(1.0f));
    const glm::vec3 half = beerTransmittance(sigma, 1.0f);
    EXPECT_NEAR(half.z * half.z, t.z, 1e-6f);
}

// ---- Perlin noise

TEST(PerlinNoise, MatchesPerlinsReferenceImplementation) {
    // The value Perlin's ImprovedNoise.java gives for noise(3.14, 42, 7).
    EXPECT_NEAR(perlinNoise({3.14f, 42.0f, 7.0f}), 0.136919958784, 2e-6);
}

TEST(PerlinNoise, IsZeroAtLatticePoints) {
    for (int x = -6; x <= 6; ++x)
        for (int y = -6; y <= 6; ++y)
            for (int z = -6; z <= 6; ++z) EXPECT_EQ(perlinNoise(glm::vec3(x, y, z) * 1.0f), 0.0f);
}

TEST(PerlinNoise, StaysWithinItsBoundAndIsDeterministic) {
    SampleRng rng(7, 7, 7);
    float largest = 0.0f, lowest = 0.0f, highest = 0.0f;
    for (int i = 0; i < 400000; ++i) {
        const glm::vec3 p(rng.next() * 64.0f - 32.0f, rng.next() * 64.0f - 32.0f, rng.next() * 64.0f - 32.0f);
        const float n = perlinNoise(p);
        ASSERT_EQ(n, perlinNoise(p));
        largest = std::max(largest, std::abs(n));
        lowest = std::min(lowest, n);
        highest = std::max(highest, n);
    }
    EXPECT_LE(largest, kPerlinNoiseBound);
    EXPECT_LT(lowest, -0.6f);  // and it uses its range
    EXPECT_GT(highest, 0.6f);
    // 1 itself is not a bound: near this point the corner gradients line up.
    const float peak = std::abs(perlinNoise({167.361633f, 55.487606f, 5.476272f}));
    EXPECT_GT(peak, 1.02f);
    EXPECT_LE(peak, kPerlinNoiseBound);
}

TEST(PerlinNoise, IsContinuous) {
    // The gradient of improved noise is bounded (by a few units), so small steps change it little.
    SampleRng rng(3, 1, 4);
    const float step = 1e-3f;
    for (int i = 0; i < 20000; ++i) {
        const glm::vec3 p(rng.next() * 20.0f - 10.0f, rng.next() * 20.0f - 10.0f, rng.next() * 20.0f - 10.0f);
        const glm::vec3 d = glm::normalize(glm::vec3(rng.next() - 0.5f, rng.next() - 0.5f, rng.next() - 0.5f));
        EXPECT_LT(std::abs(perlinNoise(p + step * d) - perlinNoise(p)), 10.0f * step) << p.x << " " << p.y << " " << p.z;
    }
}

TEST(PerlinNoise, OctaveSums) {
    SampleRng rng(5, 5, 5);
    for (int i = 0; i < 2000; ++i) {
        const glm::vec3 p(rng.next() * 10.0f, rng.next() * 10.0f, rng.next() * 10.0f);
        EXPECT_EQ(fbm(p, 1), perlinNoise(p));
        EXPECT_FLOAT_EQ(fbm(p, 2), perlinNoise(p) + 0.5f * perlinNoise(2.0f * p));
        EXPECT_FLOAT_EQ(turbulence(p, 2), std::abs(perlinNoise(p)) + 0.5f * std::abs(perlinNoise(2.0f * p)));
        EXPECT_LE(std::abs(fbm(p, 6)), 2.0f * kPerlinNoiseBound);  // the sum of 1/f is below 2
        EXPECT_GE(turbulence(p, 6), 0.0f);
        EXPECT_LE(std::abs(marble(p, 4)), 1.0f);
    }
}

// ---- textures

TEST(Texture, CheckerAlternatesBetweenCubes) {
    Texture checker;
    checker.color0 = glm::vec3(0.1f, 0.2f, 0.3f);
    checker.color1 = glm::vec3(0.9f);
    checker.scale = 2.0f;  // cubes of side 0.5
    EXPECT_EQ(evaluateColor(checker, {0.25f, 0.25f, 0.25f}, {}), checker.color0);
    EXPECT_EQ(evaluateColor(checker, {0.75f, 0.25f, 0.25f}, {}), checker.color1);
    EXPECT_EQ(evaluateColor(checker, {0.75f, 0.75f, 0.25f}, {}), checker.color0);
    EXPECT_EQ(evaluateColor(checker, {-0.25f, 0.25f, 0.25f}, {}), checker.color1);
    EXPECT_EQ(evaluateScalar(checker, {0.75f, 0.25f, 0.25f}, {}), 0.9f);
}

TEST(Texture, PatternsStayBetweenTheirColors) {
    SampleRng rng(9, 9, 9);
    for (const TextureType type : {TextureType::Noise, TextureType::Fbm, TextureType::Turbulence, TextureType::Marble}) {
        Texture texture;
        texture.type = type;
        texture.color0 = glm::vec3(0.2f, 0.4f, 0.0f);
        texture.color1 = glm::vec3(0.6f, 0.4f, 1.0f);
        texture.scale = 3.0f;
        for (int i = 0; i < 2000; ++i) {
            const glm::vec3 p(rng.next() * 4.0f, rng.next() * 4.0f, rng.next() * 4.0f);
            const glm::vec3 c = evaluateColor(texture, p, {});
            EXPECT_EQ(c, evaluateColor(texture, p, {}));
            EXPECT_GE(c.x, 0.2f);
            EXPECT_LE(c.x, 0.6f);
            EXPECT_FLOAT_EQ(c.y, 0.4f);
            EXPECT_NEAR(c.z, (c.x - 0.2f) / 0.4f, 1e-5f);  // one blend weight for all channels
        }
    }
}

TEST(Texture, ImageIsBilinearAndRepeats) {
    auto image = std::make_shared<Image>(2, 2, 3);
    // Top row (v near 1): red, green; bottom row (v near 0): blue, white.
    const glm::vec3 red(1, 0, 0), green(0, 1, 0), blue(0, 0, 1), white(1);
    const glm::vec3 pixels[4] = {red, green, blue, white};
    for (int i = 0; i < 4; ++i)
        for (int c = 0; c < 3; ++c) image->pixels[size_t(i) * 3 + c] = pixels[i][c];
    Texture texture;
    texture.type = TextureType::Image;
    texture.image = image;
    const glm::vec3 p(0.0f);
    EXPECT_EQ(evaluateColor(texture, p, {0.25f, 0.75f}), red);
    EXPECT_EQ(evaluateColor(texture, p, {0.75f, 0.75f}), green);
    EXPECT_EQ(evaluateColor(texture, p, {0.25f, 0.25f}), blue);
    EXPECT_EQ(evaluateColor(texture, p, {0.75f, 0.25f}), white);
    EXPECT_EQ(evaluateColor(texture, p, {1.25f, -0.75f}), blue);  // repeats
    const glm::vec3 center = evaluateColor(texture, p, {0.5f, 0.5f});
    EXPECT_NEAR(center.x, 0.5f, 1e-6f);
    EXPECT_NEAR(center.y, 0.5f, 1e-6f);
    EXPECT_NEAR(center.z, 0.5f, 1e-6f);
    const glm::vec3 edge = evaluateColor(texture, p, {0.0f, 0.75f});  // halfway between green and red, wrapped
    EXPECT_NEAR(edge.x, 0.5f, 1e-6f);
    EXPECT_NEAR(edge.y, 0.5f, 1e-6f);
}

// ---- material helpers

TEST(MaterialModel, TexturesReplaceConstants) {
    Material m;
    m.color = glm::vec3(0.3f);
    m.roughness = 0.25f;
    EXPECT_EQ(materialColor(m, {}, {}), glm::vec3(0.3f));
    EXPECT_EQ(materialRoughness(m, {}, {}), 0.25f);
    Texture checker;
    checker.color0 = glm::vec3(0.7f);
    m.colorTexture = checker;
    m.roughnessTexture = checker;
    EXPECT_EQ(materialColor(m, {0.5f, 0.5f, 0.5f}, {}), glm::vec3(0.7f));
    EXPECT_EQ(materialRoughness(m, {0.5f, 0.5f, 0.5f}, {}), 0.7f);
}

TEST(MaterialModel, PresetsAreTheMeasuredMetals) {
    EXPECT_EQ(conductorPresetNames(), (std::vector<std::string>{"aluminium", "copper", "gold", "silver"}));
    EXPECT_FALSE(conductorPreset("brass"));
    EXPECT_FLOAT_EQ(conductorPreset("gold")->eta.x, 0.1431189557f);
}

TEST(MaterialModel, BlinnPhongPeaksAtTheHalfVector) {
    const glm::vec3 n(0, 0, 1);
    const glm::vec3 l = glm::normalize(glm::vec3(1, 0, 1)), v = glm::normalize(glm::vec3(-1, 0, 1));
    EXPECT_NEAR(blinnPhong(n, l, v, 32.0f), 40.0f / (8.0f * float(kPi)), 1e-5f);
    EXPECT_LT(blinnPhong(n, l, glm::normalize(glm::vec3(0, 1, 1)), 32.0f), 0.1f);
}

TEST(MaterialModel, GlossyLobeNarrowsWithRoughness) {
    const glm::vec3 ideal = glm::normalize(glm::vec3(0.3f, 0.9f, -0.2f));
    EXPECT_EQ(glossyDirection(ideal, 0.0f, 0.3f, 0.7f), ideal);
    SampleRng rng(4, 4, 4);
    double smooth = 0.0, rough = 0.0;
    for (int i = 0; i < 4000; ++i) {
        const float u1 = rng.next(), u2 = rng.next();
        const glm::vec3 a = glossyDirection(ideal, 0.2f, u1, u2), b = glossyDirection(ideal, 0.8f, u1, u2);
        EXPECT_NEAR(glm::length(a), 1.0f, 1e-5f);
        EXPECT_GE(glm::dot(b, ideal), -1e-6f);  // within the hemisphere around the ideal direction
        smooth += glm::dot(a, ideal);
        rough += glm::dot(b, ideal);
    }
    EXPECT_GT(smooth / 4000, 0.99);
    EXPECT_LT(rough / 4000, smooth / 4000);
}

} // namespace
} // namespace wideray
