// The path tracer (render.integrator "path") against closed forms: a white furnace (every pixel is
// the background, whatever the bounces), the interreflections inside a diffuse sphere, a diffuse plane
// lit by a sphere light and a quad light, and by triangle lights (the irradiance of each in closed
// form, the lights' samples and the hits of sampled directions combined by multiple importance
// sampling); and the determinism the renderer promises.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "io/scene_parser.h"
#include "render/camera.h"
#include "render_helpers.h"

namespace wideray {
namespace {

Image renderPath(const SceneDescription& scene, int threads, int width, int height, ShadingOrder order = ShadingOrder::Material) {
    RenderOptions options;
    options.width = width;
    options.height = height;
    options.shadingOrder = order;
    return renderWithReference(scene, threads, options);
}

double meanOf(const Image& image, int channel) {
    double sum = 0;
    for (size_t i = size_t(channel); i < image.pixels.size(); i += 3) sum += image.pixels[i];
    return sum / double(image.pixels.size() / 3);
}

// Inside an open tube of albedo-1 diffuse walls, with a mirror ball and a glass ball in it, in a
// uniform white background: light is neither lost nor made however often a path bounces before it
// leaves through an end (Russian roulette included), so the image is the background everywhere.
TEST(PathTracer, WhiteFurnaceShowsOnlyTheBackground) {
    const SceneDescription scene = parseScene(R"({
        "camera": {"position": [0, 0, 1], "look_at": [0.3, -0.2, -1], "fov": 60},
        "image": {"spp": 32},
        "background": [1, 1, 1],
        "render": {"integrator": "path", "max_depth": 1024},
        "materials": {"white": {"type": "diffuse", "color": [1, 1, 1]},
                      "mirror": {"type": "mirror", "color": [1, 1, 1]},
                      "glass": {"type": "dielectric", "ior": 1.5}},
        "objects": [
          {"type": "generated", "shape": "quad", "material": "white", "transform": {"scale": [0.5, 1, 3], "translate": [0, -0.5, 0]}},
          {"type": "generated", "shape": "quad", "material": "white", "transform": {"scale": [0.5, 1, 3], "translate": [0, 0.5, 0]}},
          {"type": "generated", "shape": "quad", "material": "white",
           "transform": {"scale": [0.5, 1, 3], "rotate": {"axis": [0, 0, 1], "degrees": 90}, "translate": [-0.5, 0, 0]}},
          {"type": "generated", "shape": "quad", "material": "white",
           "transform": {"scale": [0.5, 1, 3], "rotate": {"axis": [0, 0, 1], "degrees": 90}, "translate": [0.5, 0, 0]}},
          {"type": "sphere", "center": [0.2, -0.3, -0.8], "radius": 0.2, "material": "mirror"},
          {"type": "sphere", "center": [-0.2, 0.2, -1.5], "radius": 0.25, "material": "glass"}]})",
                                   "furnace.json");
    const Image image = renderPath(scene, 2, 48, 36);
    // Every path carries exactly 1 until it leaves, so there is no noise to allow for.
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(meanOf(image, c), 1.0, 1e-3) << "channel " << c;
    size_t far = 0;
    for (float v : image.pixels) far += std::abs(v - 1.0f) > 0.01f;
    EXPECT_EQ(far, 0u);
}

// A point light at the center of a closed diffuse sphere of albedo rho and radius R: every bounce
// spreads the light uniformly over the sphere, so the radiance everywhere inside is the sum of a
// geometric series, rho I / (pi R^2 (1 - rho)). Half the light is lost at each bounce, so Russian
// roulette decides most paths' length.
TEST(PathTracer, InterreflectionInsideADiffuseSphereSumsTheGeometricSeries) {
    const float albedo = 0.5f, intensity = 2.0f, radius = 1.0f;
    const SceneDescription scene = parseScene(R"({
        "camera": {"position": [0.2, -0.3, 0.1], "look_at": [1, 0, 0], "fov": 90},
        "image": {"spp": 64},
        "render": {"integrator": "path", "max_depth": 1024},
        "materials": {"grey": {"type": "diffuse", "color": [0.5, 0.5, 0.5]}},
        "lights": [{"type": "point", "position": [0, 0, 0], "intensity": 2}],
        "objects": [{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "grey"}]})",
                                   "sphere_inside.json");
    const Image image = renderPath(scene, 2, 24, 24);
    const double expected = albedo * intensity / (M_PI * radius * radius * (1.0 - albedo));
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(meanOf(image, c) / expected, 1.0, 0.01) << "channel " << c;
}

/// The projected solid angle of a polygon seen from `x` with normal `n` (Lambert's formula).
float projectedSolidAngle(const glm::vec3& x, const glm::vec3& n, const glm::vec3* corners, int count) {
    float sum = 0.0f;
    for (int i = 0; i < count; ++i) {
        const glm::vec3 a = glm::normalize(corners[i] - x), b = glm::normalize(corners[(i + 1) % count] - x);
        sum += std::acos(std::clamp(glm::dot(a, b), -1.0f, 1.0f)) * glm::dot(glm::normalize(glm::cross(a, b)), n);
    }
    return 0.5f * std::abs(sum);
}

/// Renders a scene whose camera looks down at the plane y = 0 and compares every pixel with
/// `expected(p)`, the radiance the plane sends back from the point p it shows: the mean within 1%,
/// the per-pixel noise at 64 samples within 8%.
template <class Expected>
void expectPlaneRadiance(const SceneDescription& scene, Expected expected) {
    const int width = 40, height = 40;
    const Image image = renderPath(scene, 2, width, height);
    const CameraModel camera(scene.camera, width, height);
    double sumImage = 0, sumExpected = 0, sumError = 0;
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const Ray r = camera.generate(float(x) + 0.5f, float(y) + 0.5f);
            const float t = -r.oy / r.dy;
            const double want = expected(glm::vec3(r.ox + t * r.dx, 0.0f, r.oz + t * r.dz));
            const double actual = image.pixels[(size_t(y) * width + x) * 3];
            sumImage += actual;
            sumExpected += want;
            sumError += std::abs(actual - want);
        }
    EXPECT_NEAR(sumImage / sumExpected, 1.0, 0.01);
    EXPECT_LT(sumError / sumExpected, 0.08);
}

constexpr const char* kLitPlane = R"(
        "camera": {"position": [0, 3, 0], "look_at": [0, 0, 0], "up": [0, 0, -1], "fov": 40},
        "image": {"spp": 64},
        "render": {"integrator": "path"},
        "materials": {"white": {"type": "diffuse", "color": [0.8, 0.8, 0.8]}},
        "objects": [{"type": "generated", "shape": "quad", "material": "white", "transform": {"scale": 10}}],)";

TEST(PathTracer, DiffusePlaneUnderSphereAndQuadLightsMatchesTheirIrradiance) {
    const float albedo = 0.8f, sphereRadiance = 4.0f, quadRadiance = 3.0f, radius = 0.4f;
    const glm::vec3 center(1.6f, 1.0f, 0.0f);
    const glm::vec3 corners[4] = {{-2.4f, 1.2f, -0.5f}, {-1.4f, 1.2f, -0.5f}, {-1.4f, 1.2f, 0.5f}, {-2.4f, 1.2f, 0.5f}};
    const SceneDescription scene = parseScene(std::string("{") + kLitPlane + R"(
        "lights": [{"type": "sphere", "center": [1.6, 1, 0], "radius": 0.4, "intensity": 4, "samples": 2},
                   {"type": "quad", "corner": [-2.4, 1.2, -0.5], "edge_u": [1, 0, 0], "edge_v": [0, 0, 1],
                    "intensity": 3, "samples": 2}]})",
                                              "lit_plane.json");
    expectPlaneRadiance(scene, [&](glm::vec3 p) {
        const glm::vec3 toCenter = center - p;
        const float d = glm::length(toCenter);
        // A sphere wholly above the horizon: E = pi L (r / d)^2 cos(theta).
        const float sphereIrradiance = float(M_PI) * sphereRadiance * (radius / d) * (radius / d) * (toCenter.y / d);
        const float quadIrradiance = quadRadiance * projectedSolidAngle(p, glm::vec3(0, 1, 0), corners, 4);
        return albedo / M_PI * (sphereIrradiance + quadIrradiance);
    });
}

TEST(PathTracer, DiffusePlaneUnderTriangleLightsMatchesTheirIrradiance) {
    // One level triangle and one tilted, both emitting downward (edge_u x edge_v points down).
    const glm::vec3 level[3] = {{-2.4f, 1.2f, -0.5f}, {-1.4f, 1.2f, -0.5f}, {-2.4f, 1.2f, 0.5f}};
    const glm::vec3 tilted[3] = {{0.6f, 1.0f, -0.6f}, {1.8f, 1.0f, -0.6f}, {0.6f, 1.3f, 0.5f}};
    const SceneDescription scene = parseScene(std::string("{") + kLitPlane + R"(
        "lights": [{"type": "triangle", "corner": [-2.4, 1.2, -0.5], "edge_u": [1, 0, 0], "edge_v": [0, 0, 1],
                    "intensity": 3, "samples": 2},
                   {"type": "triangle", "corner": [0.6, 1, -0.6], "edge_u": [1.2, 0, 0], "edge_v": [0, 0.3, 1.1],
                    "intensity": 5, "samples": 2}]})",
                                              "triangle_lights.json");
    expectPlaneRadiance(scene, [&](glm::vec3 p) {
        const glm::vec3 up(0, 1, 0);
        return 0.8 / M_PI * (3.0f * projectedSolidAngle(p, up, level, 3) + 5.0f * projectedSolidAngle(p, up, tilted, 3));
    });
}

TEST(PathTracer, SameImageWithAnyThreadCountAndInAnyShadingOrder) {
    SceneDescription scene = loadScene(std::filesystem::path(WIDERAY_SOURCE_DIR) / "scenes" / "default.json");
    scene.render.integrator = Integrator::Path;
    scene.image.samplesPerPixel = 2;
    const Image one = renderPath(scene, 1, 64, 48), two = renderPath(scene, 2, 64, 48);
    EXPECT_TRUE(one.pixels == two.pixels);
    // The same samples, added to the pixels in another order: equal up to rounding.
    const Image byRay = renderPath(scene, 2, 64, 48, ShadingOrder::Ray);
    ASSERT_EQ(byRay.pixels.size(), two.pixels.size());
    for (size_t i = 0; i < two.pixels.size(); ++i) ASSERT_NEAR(byRay.pixels[i], two.pixels[i], 1e-5f * (1 + two.pixels[i]));
}

TEST(PathTracer, UnknownIntegratorNamesTheKeyAndTheChoices) {
    try {
        parseScene(R"({"render": {"integrator": "pathh"}})", "bad.json");
        FAIL() << "accepted";
    } catch (const std::exception& e) {
        const std::string message = e.what();
        EXPECT_NE(message.find("render.integrator"), std::string::npos) << message;
        EXPECT_NE(message.find("path"), std::string::npos) << message;
    }
}

} // namespace
} // namespace wideray
