// Motion blur: a ray's time moves analytic objects and two-level instances between their two
// transforms. At times 0 and 1 the moving scene is the static scene at either transform; between
// them the boxes bound the motion (every backend and kernel agrees at random times); the camera
// samples the shutter deterministically; scene keys and their errors.
#include <gtest/gtest.h>

#include <random>

#include <glm/gtc/matrix_transform.hpp>

#include "backend_trace.h"
#include "core/fp_mode.h"
#include "geometry/analytic_geometry.h"
#include "io/mesh_generators.h"
#include "io/scene_parser.h"
#include "render/bench_rays.h"
#include "render_helpers.h"
#include "scene_errors.h"

namespace wideray {
namespace {

const glm::mat4 kStart = glm::translate(glm::mat4(1.0f), glm::vec3(-1.5f, 0.0f, 0.0f));
const glm::mat4 kEnd = glm::rotate(glm::translate(glm::mat4(1.0f), glm::vec3(1.5f, 0.5f, 0.0f)), 0.7f, glm::vec3(0, 0, 1));

/// A torus mesh instanced twice and an ellipsoid, moving from kStart to kEnd (or still at `at`), over
/// a floor.
SceneDescription movingScene(std::optional<glm::mat4> at) {
    SceneDescription scene;
    scene.materials = {{"grey"}};
    scene.meshes = {makeTorus(0.6f, 0.25f, 24, 12), makeQuad()};
    const glm::mat4 offset = glm::translate(glm::mat4(1.0f), glm::vec3(0, 0, -1.5f));
    for (const glm::mat4& place : {glm::mat4(1.0f), offset}) {
        MeshInstance instance{0, (at ? *at : kStart) * place};
        if (!at) instance.endTransform = kEnd * place;
        scene.instances.push_back(instance);
    }
    scene.instances.push_back({1, glm::scale(glm::translate(glm::mat4(1.0f), glm::vec3(0, -1, 0)), glm::vec3(5.0f))});
    AnalyticObject ball;
    ball.transform = (at ? *at : kStart) * glm::translate(glm::mat4(1.0f), glm::vec3(0, 1.2f, 0)) * glm::scale(glm::mat4(1.0f), glm::vec3(0.4f));
    if (!at) ball.endTransform = kEnd * glm::translate(glm::mat4(1.0f), glm::vec3(0, 1.2f, 0)) * glm::scale(glm::mat4(1.0f), glm::vec3(0.4f));
    scene.analytics.push_back(ball);
    scene.camera.position = {0.0f, 2.0f, 6.0f};
    scene.camera.lookAt = {0.0f, 0.0f, -0.5f};
    return scene;
}

std::vector<Ray> raysAt(const SceneDescription& scene, float time) {
    std::vector<Ray> rays = primaryRays(scene, 64, 48);
    for (Ray& r : rays) r.time = time;
    return rays;
}

TEST(MotionBlur, TheEndsAreTheStaticScenes) {
    FlushToZeroScope ftz;
    auto moving = std::make_shared<const SceneGeometry>(movingScene(std::nullopt), Instancing::TwoLevel);
    ASSERT_NE(moving->instances(), nullptr) << "moving instances are two-level";
    for (const auto& [time, transform] : {std::pair{0.0f, kStart}, std::pair{1.0f, kEnd}}) {
        // The static scene with the same geometries (all two-level), so that ids compare.
        auto still = std::make_shared<const SceneGeometry>(movingScene(transform), Instancing::TwoLevel);
        const std::vector<Ray> rays = raysAt(movingScene(transform), time);
        for (const char* backend : {"wideray", "embree"}) {
            const std::vector<Hit> a = testing::traceThrough(moving, backend, "", rays), b = testing::traceThrough(still, backend, "", rays);
            size_t hits = 0, differ = 0;
            for (size_t i = 0; i < rays.size(); ++i) {
                hits += a[i].valid();
                const bool same = a[i].valid() == b[i].valid() &&
                                  (!a[i].valid() || (a[i].geomId == b[i].geomId && a[i].primId == b[i].primId &&
                                                     std::fabs(a[i].t - b[i].t) <= 1e-5f * b[i].t));
                differ += !same;
            }
            EXPECT_GT(hits, rays.size() / 3) << backend << " time " << time;
            EXPECT_LE(differ, rays.size() / 1000) << backend << " time " << time;  // ties on edges
        }
    }
}

TEST(MotionBlur, EveryBackendAndKernelAgreesAtAnyTime) {
    // Between the ends the objects leave both end boxes' union only if the bounds were wrong: the
    // wide BVH would then miss what Embree finds (its motion BVH bounds the motion itself).
    FlushToZeroScope ftz;
    const SceneDescription scene = movingScene(std::nullopt);
    auto geometry = std::make_shared<const SceneGeometry>(scene);
    std::vector<Ray> rays = primaryRays(scene, 96, 72);
    std::mt19937 rng(3);
    for (Ray& r : rays) r.time = std::uniform_real_distribution<float>(0.0f, 1.0f)(rng);
    const std::vector<Hit> reference = testing::traceThrough(geometry, "wideray", "", rays);
    size_t moving = 0;
    for (const Hit& h : reference) moving += h.valid() && h.geomId != 0;
    EXPECT_GT(moving, rays.size() / 20);
    for (const char* kernel : {"single", "packet4", "packet256", "stream"}) {
        std::vector<Hit> hits(rays.size());
        buildWideBvh(geometry, {})->tracer({kernel})->intersect(rays, hits, Coherence::Coherent);
        size_t differ = 0;
        for (size_t i = 0; i < rays.size(); ++i)
            differ += hits[i].valid() != reference[i].valid() || hits[i].primId != reference[i].primId || hits[i].t != reference[i].t;
        EXPECT_EQ(differ, 0u) << kernel;
    }
    const std::vector<Hit> embree = testing::traceThrough(geometry, "embree", "", rays);
    size_t differ = 0;
    for (size_t i = 0; i < rays.size(); ++i)
        differ += embree[i].valid() != reference[i].valid() || (reference[i].valid() && embree[i].primId != reference[i].primId);
    EXPECT_LE(differ, rays.size() / 200);
}

TEST(MotionBlur, AMovingBallIsWhereItsTimePutsIt) {
    // A unit ball moving from x = -2 to x = 2: a ray down the z axis meets it only around time 0.5,
    // at the distance of its front at that time.
    AnalyticObject ball;
    ball.transform = glm::translate(glm::mat4(1.0f), glm::vec3(-2, 0, 0));
    ball.endTransform = glm::translate(glm::mat4(1.0f), glm::vec3(2, 0, 0));
    const AnalyticGeometry geometry({ball});
    for (float time : {0.0f, 0.2f, 0.45f, 0.5f, 0.55f, 0.8f, 1.0f}) {
        Ray r{0, 0, 5, 0, 0, -1};
        r.time = time;
        const float x = -2.0f + 4.0f * time;  // the center
        float t, u, v;
        const bool hit = geometry.intersect(r, 0, r.tfar, t, u, v);
        ASSERT_EQ(hit, std::fabs(x) < 1.0f) << time;
        if (hit) {
            EXPECT_NEAR(t, 5.0f - std::sqrt(1.0f - x * x), 1e-5f) << time;
        }
    }
    EXPECT_LE(geometry.primitiveBounds(0).lower.x, -3.0f);
    EXPECT_GE(geometry.primitiveBounds(0).upper.x, 3.0f);
}

constexpr const char* kBlurScene = R"({
  "camera": {"position": [0, 1, 6], "look_at": [0, 0.5, 0], "shutter": [0, 1]},
  "image": {"width": 48, "height": 32, "spp": 8},
  "lights": [{"type": "point", "position": [2, 5, 4], "intensity": 30}],
  "materials": {"red": {"type": "diffuse", "color": [0.8, 0.1, 0.1]}},
  "objects": [
    {"type": "generated", "shape": "quad", "transform": {"scale": 5}},
    {"type": "sphere", "center": [0, 0.6, 0], "radius": 0.5, "material": "red",
     "transform": {"translate": [-1.5, 0, 0]}, "end_transform": {"translate": [1.5, 0, 0]}},
    {"type": "generated", "shape": "torus", "transform": {"translate": [0, 0.3, -1.5]},
     "end_transform": {"translate": [0, 1.3, -1.5]}, "repeat": {"count": [2, 1, 1], "step": [2.5, 0, 0]}}
  ]
})";

TEST(MotionBlur, TheShutterIsSampledDeterministically) {
    const SceneDescription scene = parseScene(kBlurScene, "blur.json");
    EXPECT_EQ(scene.camera.shutterClose, 1.0f);
    ASSERT_EQ(scene.analytics.size(), 1u);
    EXPECT_TRUE(scene.analytics[0].endTransform.has_value());
    ASSERT_EQ(scene.instances.size(), 3u);
    EXPECT_TRUE(scene.instances[1].endTransform.has_value());
    const Image a = renderWithReference(scene, 1, {}), b = renderWithReference(scene, 2, {});
    EXPECT_EQ(a.pixels, b.pixels);
    // The ball's track is smeared: pixels on it are partly red, partly floor.
    SceneDescription still = scene;
    still.camera.shutterClose = 0.0f;  // every ray at time 0
    const Image sharp = renderWithReference(still, 2, {});
    EXPECT_NE(sharp.pixels, a.pixels);
    int blurred = 0;
    for (int x = 0; x < a.width; ++x) {
        const float* p = a.at(x, 13);
        blurred += p[0] > 1.5f * p[1] && p[1] > 0.02f;  // reddish, not pure
    }
    EXPECT_GT(blurred, 10);
    // The writer keeps the motion.
    const SceneDescription written = parseScene(writeScene(scene), "written.json");
    ASSERT_TRUE(written.analytics[0].endTransform.has_value());
    EXPECT_EQ(*written.analytics[0].endTransform, *scene.analytics[0].endTransform);
    EXPECT_EQ(written.camera.shutterClose, 1.0f);
    EXPECT_TRUE(written.instances[2].endTransform.has_value());
}

TEST(MotionBlur, BadKeysNameTheirPath) {
    auto cameraError = [](const std::string& camera) {
        try {
            parseScene(R"({"camera": )" + camera + R"(, "objects": [{"type": "generated", "shape": "cube"}]})", "bad.json");
        } catch (const InputError& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    EXPECT_NE(cameraError(R"({"shutter": [0.5, 0.2]})").find("camera.shutter"), std::string::npos);
    EXPECT_NE(cameraError(R"({"shutter": [0, 2]})").find("camera.shutter"), std::string::npos);
    const auto error = testing::objectError;
    EXPECT_NE(error(R"({"type": "torus", "end_transform": {"scale": 0}})").find("objects[0].end_transform.scale"), std::string::npos);
    EXPECT_NE(error(R"({"type": "csg", "operation": "union", "operands": [{"type": "sphere", "center": [0, 0, 0], "radius": 1,
        "end_transform": {"translate": [1, 0, 0]}}, {"type": "sphere", "center": [0, 0, 0], "radius": 1}]})")
                  .find("operands[0].end_transform"),
              std::string::npos);
    EXPECT_NE(error(R"({"type": "heightfield", "end_transform": {}})").find("end_transform"), std::string::npos);
    // Interpolated entry by entry, a half turn or a mirroring passes through a singular matrix.
    EXPECT_NE(error(R"({"type": "torus", "end_transform": {"rotate": {"axis": [0, 0, 1], "degrees": 180}}})").find("singular"),
              std::string::npos);
    EXPECT_NE(error(R"({"type": "generated", "shape": "cube", "end_transform": {"scale": [-1, 1, 1]}})").find("objects[0].end_transform"),
              std::string::npos);
    EXPECT_EQ(error(R"({"type": "sphere", "center": [0, 0, 0], "radius": 1, "end_transform": {"rotate": {"axis": [0, 1, 0], "degrees": 90}}})"),
              "no error");
}

} // namespace
} // namespace wideray
