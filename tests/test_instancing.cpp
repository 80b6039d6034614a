// Two-level instancing: hits through instances equal the flattened scene's (same primitive and
// instance, t within a bound; normals and materials of turned, scaled and mirrored instances), through
// our BVHs and Embree's instances; which meshes Auto makes two-level; memory of many instances; CLI.
#include <gtest/gtest.h>

#include <cmath>

#include "backend_trace.h"
#include "backends/wideray_structure.h"
#include "core/fp_mode.h"
#include "geometry/triangle_geometry.h"
#include "instanced_scene.h"
#include "io/mesh_generators.h"
#include "ray_sets.h"
#include "render/bench_rays.h"
#include "render/image_difference.h"
#include "render_helpers.h"
#include "io/scene_parser.h"
#include "scene_errors.h"

namespace wideray {
namespace {

/// The flattened scene's triangles are geomId 0; the two-level scene's, the instance geometry's.
bool sameSurface(const SceneGeometry& flat, const Hit& a, const SceneGeometry& twoLevel, const Hit& b, const Ray& ray) {
    if (a.valid() != b.valid()) return false;
    if (!a.valid()) return true;
    const bool aTriangle = flat[a.geomId].triangles() != nullptr, bTriangle = twoLevel[b.geomId].instances() != nullptr;
    if (aTriangle != bTriangle || a.primId != b.primId) return false;
    // Object space rounds the ray and the vertices differently: t agrees to a few ulps of the reach.
    const float reach = std::fabs(ray.ox) + std::fabs(ray.oy) + std::fabs(ray.oz) + 20.0f;
    return std::fabs(a.t - b.t) <= 1e-5f * reach;
}

TEST(Instancing, HitsEqualTheFlattenedScenes) {
    FlushToZeroScope ftz;
    const SceneDescription scene = testing::instancedScene();
    auto flat = std::make_shared<const SceneGeometry>(scene, Instancing::Flatten);
    auto twoLevel = std::make_shared<const SceneGeometry>(scene, Instancing::TwoLevel);
    ASSERT_EQ(flat->instances(), nullptr);
    ASSERT_NE(twoLevel->instances(), nullptr);
    EXPECT_EQ(twoLevel->instances()->primitiveCount(), scene.instances.size());
    EXPECT_EQ(twoLevel->instancedTriangleCount(), flat->triangleCount());
    std::vector<Ray> rays = primaryRays(scene, 64, 64);
    const std::vector<Ray> random = testing::randomRays(flattenTriangles(scene), 4000, 9);
    rays.insert(rays.end(), random.begin(), random.end());
    const std::vector<Hit> expected = testing::traceThrough(flat, "wideray", "bvh8", rays);
    for (const char* backend : {"wideray", "embree"}) {
        for (const char* accel : {"bvh8", "bvh4", "bvh16"}) {
            if (std::string(backend) == "embree" && std::string(accel) != "bvh8") continue;
            const std::vector<Hit> hits = testing::traceThrough(twoLevel, backend, std::string(backend) == "embree" ? "" : accel, rays);
            size_t differ = 0, instanced = 0;
            for (size_t i = 0; i < rays.size(); ++i) {
                instanced += hits[i].valid() && (*twoLevel)[hits[i].geomId].instances();
                if (sameSurface(*flat, expected[i], *twoLevel, hits[i], rays[i])) {
                    if (!hits[i].valid() || !(*twoLevel)[hits[i].geomId].instances()) continue;
                    // The same instance, material and facing, whatever the transform (one is mirrored).
                    const SurfacePoint a = flat->surface(rays[i], expected[i]), b = twoLevel->surface(rays[i], hits[i]);
                    EXPECT_EQ(a.instance, b.instance) << backend << " ray " << i;
                    EXPECT_EQ(a.material, b.material) << backend << " ray " << i;
                    EXPECT_GT(glm::dot(a.geometricNormal, b.geometricNormal), 0.9999f) << backend << " ray " << i;
                    EXPECT_LT(glm::length(a.position - b.position), 1e-5f * (glm::length(a.position) + glm::length(glm::vec3(rays[i].ox, rays[i].oy, rays[i].oz)) + 10.0f)) << backend << " ray " << i;
                } else if (++differ <= 3) {
                    ADD_FAILURE() << backend << " " << accel << " ray " << i << ": " << hits[i].geomId << "/" << hits[i].primId
                                  << " t " << hits[i].t << " vs flattened " << expected[i].geomId << "/" << expected[i].primId
                                  << " t " << expected[i].t;
                }
            }
            // Rays through an edge may take either triangle when the arithmetic differs (Embree's
            // test is not watertight): a few in a thousand.
            EXPECT_LE(differ, rays.size() / 500) << backend << " " << accel;
            EXPECT_GT(instanced, rays.size() / 3) << backend;
        }
    }
}

TEST(Instancing, ShadowRaysAndRendersMatchTheFlattenedScene) {
    SceneDescription scene = testing::instancedScene();
    scene.image = {48, 36, 1};
    const Image flat = [&] {
        tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 2);
        auto tracer = buildWideBvh(std::make_shared<const SceneGeometry>(scene, Instancing::Flatten), {})->tracer({});
        RenderStats stats;
        return render(scene, *tracer, {}, stats);
    }();
    for (const char* backend : {"wideray", "embree"}) {
        auto geometry = std::make_shared<const SceneGeometry>(scene, Instancing::TwoLevel);
        auto tracer = findBackend(backend).build(geometry, {})->tracer({});
        RenderStats stats;
        const Image image = render(scene, *tracer, {}, stats);
        const ImageDifference diff = compareImages(flat, image, 0.02f);
        EXPECT_LT(diff.meanAbsolute, 2e-3) << backend;
        EXPECT_LE(diff.pixelsOver, 8u) << backend;
    }
}

TEST(Instancing, AutoMakesTwoLevelWhereCopiesWouldCostMemory) {
    SceneDescription scene;
    scene.materials = {{"grey"}};
    scene.meshes = {makeQuad(), makeIcosphere(5)};  // 2 and 20480 triangles
    for (int i = 0; i < 5; ++i) scene.instances.push_back({0, glm::translate(glm::mat4(1.0f), glm::vec3(float(i), 0, 0))});
    for (int i = 0; i < 3; ++i) scene.instances.push_back({1, glm::translate(glm::mat4(1.0f), glm::vec3(0, 0, 3.0f * float(i)))});
    EXPECT_EQ(twoLevelMeshes(scene, Instancing::Auto), (std::vector<bool>{false, false}));  // 2 x 20480 copied
    for (int i = 3; i < 5; ++i) scene.instances.push_back({1, glm::translate(glm::mat4(1.0f), glm::vec3(0, 0, 3.0f * float(i)))});
    EXPECT_EQ(twoLevelMeshes(scene, Instancing::Auto), (std::vector<bool>{false, true}));  // 4 x 20480 >= 65536
    EXPECT_EQ(twoLevelMeshes(scene, Instancing::TwoLevel), (std::vector<bool>{true, true}));
    EXPECT_EQ(twoLevelMeshes(scene, Instancing::Flatten), (std::vector<bool>{false, false}));
    const SceneGeometry geometry(scene);
    EXPECT_EQ(geometry.triangleCount(), 5u * 2u + 20480u);
    EXPECT_EQ(geometry.instancedTriangleCount(), 5u * 2u + 5u * 20480u);
    // The flattened quads keep telling their scene instance.
    const auto& triangles = static_cast<const TriangleGeometry&>(geometry[0]);
    EXPECT_EQ(triangles.instanceOf(9), 4u);
    EXPECT_EQ(geometry.instances()->placements()[2].sceneInstance, 7u);
}

TEST(Instancing, RepeatPlacesCopiesAndBadValuesNameTheirKey) {
    const SceneDescription scene = parseScene(R"({"lights": [{"type": "point", "position": [0, 5, 0]}], "objects": [
        {"type": "generated", "shape": "cube", "transform": {"translate": [1, 0, 0]},
         "repeat": {"count": [3, 2, 1], "step": [4, 5, 0], "turn": 30, "seed": 2}}]})", "repeat.json");
    ASSERT_EQ(scene.instances.size(), 6u);
    EXPECT_EQ(glm::vec3(scene.instances[5].transform[3]), glm::vec3(9, 5, 0));  // (2, 1, 0) * step + the own translate
    EXPECT_NE(scene.instances[0].transform, scene.instances[3].transform * glm::translate(glm::mat4(1.0f), glm::vec3(0, -5, 0)));
    const auto error = testing::objectError;
    const std::string cube = R"({"type": "generated", "shape": "cube", "repeat": )";
    EXPECT_NE(error(cube + R"({"count": [0, 1, 1], "step": [1, 1, 1]}})").find("objects[0].repeat.count[0]"), std::string::npos);
    EXPECT_NE(error(cube + R"({"count": [1000, 1000, 2], "step": [1, 1, 1]}})").find("at most 1000000"), std::string::npos);
    EXPECT_NE(error(cube + R"({"count": [1, 1, 1]}})").find("step"), std::string::npos);
    EXPECT_NE(error(R"({"type": "csg", "operation": "union", "operands": [)" + cube + R"({"count": [2, 1, 1], "step": [1, 0, 0]}},
        {"type": "sphere", "center": [0, 0, 0], "radius": 1}]})").find("cannot be repeated"), std::string::npos);
}

TEST(Instancing, TenThousandInstancesTakeLittleMoreThanOneMesh) {
    SceneDescription scene;
    scene.materials = {{"grey"}};
    scene.meshes = {makeIcosphere(5)};
    for (int j = 0; j < 100; ++j)
        for (int i = 0; i < 100; ++i)
            scene.instances.push_back({0, glm::scale(glm::translate(glm::mat4(1.0f), glm::vec3(3.0f * float(i), 0, 3.0f * float(j))),
                                                     glm::vec3(1.0f + 0.002f * float(i + j)))});
    scene.camera.position = {-20.0f, 40.0f, -20.0f};
    scene.camera.lookAt = {150.0f, 0.0f, 150.0f};
    auto geometry = std::make_shared<const SceneGeometry>(scene);
    ASSERT_NE(geometry->instances(), nullptr);
    EXPECT_EQ(geometry->instancedTriangleCount(), 10000u * 20480u);
    auto structure = std::static_pointer_cast<const WideBvhStructure<8>>(buildWideBvh(geometry, {}));
    const SceneAccel<8>& accel = structure->accel();
    ASSERT_EQ(accel.instancedMeshes().size(), 1u);
    const size_t mesh = accel.instancedMeshes()[0]->bytes();
    EXPECT_LT(accel.bytes(), mesh + 10000 * 256) << "one mesh's structure plus a little per instance";
    EXPECT_GT(accel.flattenedBytes(), 9000 * mesh);
    const std::vector<Ray> rays = primaryRays(scene, 64, 64);
    std::vector<Hit> hits(rays.size());
    structure->tracer({})->intersect(rays, hits, Coherence::Coherent);
    size_t hit = 0;
    for (const Hit& h : hits) hit += h.valid();
    EXPECT_GT(hit, rays.size() / 2);
}

} // namespace
} // namespace wideray
