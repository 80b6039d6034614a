// The shading effects: each effect scene renders the same with one and two threads and matches its
// stored reference; small scenes check the renderer against closed forms (inverse-square falloff,
// Beer's law, mirror tint, Fresnel at normal incidence, polarization at Brewster's angle, fog).
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include <tbb/global_control.h>

#include "core/fp_mode.h"
#include "io/image_io.h"
#include "render/renderer.h"
#include "io/scene_parser.h"
#include "shading/fresnel.h"
#include "render_helpers.h"

namespace wideray {
namespace {

const std::filesystem::path kSourceDir = WIDERAY_SOURCE_DIR;
constexpr int kWidth = 80, kHeight = 60;

Image renderScene(const SceneDescription& scene, int threads, int width, int height) {
    RenderOptions options;
    options.width = width;
    options.height = height;
    return renderWithReference(scene, threads, options);
}

class EffectScene : public testing::TestWithParam<std::string> {};

TEST_P(EffectScene, IsIdenticalWithOneAndTwoThreadsAndMatchesItsReference) {
    const SceneDescription scene = loadScene(kSourceDir / "scenes" / (GetParam() + ".json"));
    const Image one = renderScene(scene, 1, kWidth, kHeight), two = renderScene(scene, 2, kWidth, kHeight);
    ASSERT_EQ(one.pixels.size(), two.pixels.size());
    EXPECT_TRUE(one.pixels == two.pixels);

    // Regenerate with: build/wideray render scenes/NAME.json --size 80x60 --kernel scalar -o tests/data/effects/NAME.png
    const Image reference = readImage(kSourceDir / "tests/data/effects" / (GetParam() + ".png"), true);
    ASSERT_EQ(reference.width, kWidth);
    ASSERT_EQ(reference.height, kHeight);
    ASSERT_EQ(reference.channels, 3);
    const std::filesystem::path written =
        std::filesystem::temp_directory_path() / ("wideray_effect_" + GetParam() + ".png");
    writeImage(two, written, true);
    const Image roundTrip = readImage(written, true);
    std::filesystem::remove(written);
    // In 8-bit sRGB steps, as stored: allow rounding and a few pixels of larger change.
    double sum = 0;
    size_t large = 0;
    for (size_t i = 0; i < reference.pixels.size(); ++i) {
        const double d = std::abs(double(roundTrip.pixels[i]) - double(reference.pixels[i]));
        sum += d;
        large += d > 0.02;
    }
    EXPECT_LT(sum / double(reference.pixels.size()), 0.002);
    EXPECT_LT(large, reference.pixels.size() / 100);
}

INSTANTIATE_TEST_SUITE_P(Scenes, EffectScene,
                         testing::Values("beer", "metals", "soft_shadows", "glossy", "dof", "textures", "fog",
                                         "polarization", "polarization_off"));

/// The single pixel seen by a 1x1 camera at `eye` looking at `lookAt`, in a scene of `body` (JSON
/// members after the camera and image).
glm::vec3 centerPixel(const std::string& eye, const std::string& lookAt, const std::string& up, const std::string& body) {
    const std::string json = R"({"camera": {"position": )" + eye + R"(, "look_at": )" + lookAt + R"(, "up": )" + up +
                             R"(}, "image": {"width": 1, "height": 1}, )" + body + "}";
    const Image image = renderScene(parseScene(json, "analytic.json"), 1, 1, 1);
    return {image.pixels[0], image.pixels[1], image.pixels[2]};
}

void expectNear(const glm::vec3& actual, const glm::vec3& expected, float relative) {
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(actual[c], expected[c], relative * expected[c]) << "channel " << c;
}

TEST(RenderAnalytic, DiffusePlaneUnderPointLightIsAlbedoOverPiTimesInverseSquare) {
    const float height = 2.0f, intensity = 5.0f;
    const glm::vec3 radiance = centerPixel("[0, 4, 0]", "[0, 0, 0]", "[0, 0, -1]", R"(
        "materials": {"white": {"type": "diffuse", "color": [1, 1, 1]}},
        "lights": [{"type": "point", "position": [0, 2, 0], "intensity": 5}],
        "objects": [{"type": "generated", "shape": "quad", "material": "white", "transform": {"scale": 10}}])");
    expectNear(radiance, glm::vec3(intensity / (float(M_PI) * height * height)), 0.01f);
}

TEST(RenderAnalytic, SlabWithoutFresnelTransmitsBeersLaw) {
    const glm::vec3 sigma(0.5f, 1.0f, 2.0f);
    const float thickness = 0.8f;
    const glm::vec3 radiance = centerPixel("[0, 0, 5]", "[0, 0, 0]", "[0, 1, 0]", R"(
        "background": [1, 1, 1],
        "materials": {"liquid": {"type": "dielectric", "ior": 1.0, "absorption": [0.5, 1, 2]}},
        "objects": [{"type": "generated", "shape": "cube", "material": "liquid", "transform": {"scale": [3, 3, 0.4]}}])");
    expectNear(radiance, glm::exp(-sigma * thickness), 0.01f);
}

TEST(RenderAnalytic, MirrorReflectsTheBackgroundTintedByItsColor) {
    const glm::vec3 radiance = centerPixel("[0, 1, 1]", "[0, 0, 0]", "[0, 1, 0]", R"(
        "background": [0.2, 0.4, 0.8],
        "materials": {"mirror": {"type": "mirror", "color": [0.9, 0.5, 0.25]}},
        "objects": [{"type": "generated", "shape": "quad", "material": "mirror", "transform": {"scale": 5}}])");
    expectNear(radiance, glm::vec3(0.18f, 0.2f, 0.2f), 1e-5f);
}

TEST(RenderAnalytic, GlassSphereAtNormalIncidenceReflectsAndTransmitsByFresnel) {
    const auto sphere = [](int maxDepth) {
        return centerPixel("[0, 0, 5]", "[0, 0, 0]", "[0, 1, 0]", R"(
            "background": [1, 1, 1], "render": {"max_depth": )" + std::to_string(maxDepth) + R"(, "min_throughput": 0},
            "materials": {"glass": {"type": "dielectric", "ior": 1.5}},
            "objects": [{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "glass"}])");
    };
    const float r = 0.04f, t = 1.0f - r;  // ((1.5 - 1) / (1.5 + 1))^2
    expectNear(sphere(1), glm::vec3(r), 1e-4f);  // the front reflection only
    expectNear(sphere(2), glm::vec3(r + t * t), 1e-4f);  // and the light passing straight through
    expectNear(sphere(32), glm::vec3(1.0f), 1e-4f);  // no absorption: all light comes out again
}

TEST(RenderAnalytic, PolarizationTrackingAtBrewstersAngle) {
    // A plate turned to Brewster's angle: the front reflection, then the light through both faces.
    const float brewster = std::atan(1.5f);
    const auto plate = [&](bool polarized) {
        return centerPixel("[0, 0, 5]", "[0, 0, 0]", "[0, 1, 0]", R"(
            "background": [1, 1, 1], "render": {"max_depth": 2, "min_throughput": 0, "polarized": )" +
                std::string(polarized ? "true" : "false") + R"(},
            "materials": {"glass": {"type": "dielectric", "ior": 1.5}},
            "objects": [{"type": "generated", "shape": "cube", "material": "glass",
                         "transform": {"scale": [3, 3, 0.1], "rotate": {"axis": [0, 1, 0], "degrees": )" +
                std::to_string(glm::degrees(brewster)) + "}}}]");
    };
    const FresnelReflectance<float> r = fresnelDielectric(std::cos(brewster), 1.5f);
    ASSERT_LT(r.p, 1e-6f);
    const float ts = 1.0f - r.s, tp = 1.0f - r.p, average = 0.5f * (ts + tp);
    expectNear(plate(true), glm::vec3(r.unpolarized() + 0.5f * (ts * ts + tp * tp)), 1e-3f);
    expectNear(plate(false), glm::vec3(r.unpolarized() + average * average), 1e-3f);
}

TEST(RenderAnalytic, FogAttenuatesTheBackgroundAcrossTheSceneBox) {
    // Two small spheres span the box z in [-4.5, 4.5] that the fog fills; the ray along -z misses them.
    const glm::vec3 radiance = centerPixel("[0, 0, 8]", "[0, 0, 0]", "[0, 1, 0]", R"(
        "background": [1, 1, 1], "fog": {"density": 0.1},
        "objects": [{"type": "sphere", "center": [0, 3, 4], "radius": 0.5},
                    {"type": "sphere", "center": [0, -3, -4], "radius": 0.5}])");
    expectNear(radiance, glm::vec3(std::exp(-0.1f * 9.0f)), 1e-4f);
}

} // namespace
} // namespace wideray
