// The scene's geometry, built once: geometries by geomId through the registry of geometry kinds,
// instances kept apart in the triangle geometry, and one BVH over triangles and user primitives.
#include <gtest/gtest.h>

#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

#include "backends/wideray_structure.h"
#include "core/error.h"
#include "core/fp_mode.h"
#include "geometry/scene_geometry.h"
#include "geometry/triangle_geometry.h"
#include "io/mesh_generators.h"
#include "kernels/kernel_registry.h"

namespace wideray {
namespace {

/// The quad [-1, 1]^2 at y = 0 placed `count` times along x, 3 apart, and spheres of radius 0.5 at
/// y = 3 above them.
SceneDescription quadsAndSpheres(int count, int spheres) {
    SceneDescription scene;
    scene.materials.push_back({});
    scene.meshes = {makeQuad()};
    for (int i = 0; i < count; ++i) {
        MeshInstance instance;
        instance.transform = glm::translate(glm::mat4(1.0f), glm::vec3(3.0f * float(i), 0.0f, 0.0f));
        scene.instances.push_back(instance);
    }
    for (int i = 0; i < spheres; ++i) scene.spheres.push_back({{3.0f * float(i), 3.0f, 0.0f}, 0.5f, 0});
    return scene;
}

Hit traceDown(const Tracer& tracer, float x, float y) {
    const Ray ray{x, y, 0.1f, 0.0f, -1.0f, 0.0f, 0.0f, 100.0f};
    Hit hit;
    tracer.intersect({&ray, 1}, {&hit, 1}, Coherence::Incoherent);
    return hit;
}

TEST(SceneGeometry, GeometriesByGeomIdFromTheRegistry) {
    const SceneGeometry geometry(quadsAndSpheres(2, 3));
    ASSERT_EQ(geometry.size(), 2u);
    ASSERT_NE(geometry[0].triangles(), nullptr);
    EXPECT_EQ(geometry[0].user(), nullptr);
    EXPECT_EQ(geometry[1].triangles(), nullptr);
    ASSERT_NE(geometry[1].user(), nullptr);
    EXPECT_EQ(geometry[1].primitiveCount(), 3u);
    EXPECT_EQ(geometry.triangleCount(), 4u);
    const Bounds3f b = geometry.bounds();  // the quads and the spheres
    EXPECT_EQ(b.lower, glm::vec3(-1.0f, 0.0f, -1.0f));
    EXPECT_EQ(b.upper, glm::vec3(6.5f, 3.5f, 1.0f));

    const SceneGeometry spheresOnly(quadsAndSpheres(0, 1));
    ASSERT_EQ(spheresOnly.size(), 2u) << "geomId 0 stays the (empty) triangles";
    EXPECT_EQ(spheresOnly.triangleCount(), 0u);
}

TEST(SceneGeometry, HitsTellTheirInstanceAndGeometry) {
    FlushToZeroScope ftz;
    auto geometry = std::make_shared<const SceneGeometry>(quadsAndSpheres(3, 2));
    const auto& triangles = static_cast<const TriangleGeometry&>((*geometry)[0]);
    for (int width : {4, 8, 16}) {
        StructureOptions options;
        options.bvhWidth = width;
        for (const char* kernel : {"scalar", "single", "packet4", "stream"}) {
            std::unique_ptr<Tracer> tracer = buildWideBvh(geometry, options)->tracer({kernel});
            for (int i = 0; i < 3; ++i) {
                const Ray ray{3.0f * float(i) + 0.1f, 1.0f, 0.1f, 0.0f, -1.0f, 0.0f, 0.0f, 100.0f};
                const Hit hit = traceDown(*tracer, ray.ox, ray.oy);
                ASSERT_TRUE(hit.valid()) << kernel << " instance " << i;
                EXPECT_EQ(hit.geomId, 0u);
                EXPECT_EQ(triangles.instanceOf(hit.primId), uint32_t(i));
                EXPECT_EQ(geometry->surface(ray, hit).instance, uint32_t(i)) << kernel;
            }
            // From above the spheres: the sphere (geomId 1) is nearer than the quad below it.
            const Hit sphere = traceDown(*tracer, 3.0f, 5.0f);
            ASSERT_TRUE(sphere.valid()) << kernel;
            EXPECT_EQ(sphere.geomId, 1u) << kernel;
            EXPECT_EQ(sphere.primId, 1u) << kernel;
            EXPECT_NEAR(sphere.t, 2.0f - std::sqrt(0.24f), 1e-5f) << kernel;  // z = 0.1 off the center
            EXPECT_FALSE(traceDown(*tracer, 8.5f, 5.0f).valid()) << kernel;
        }
    }
}

/// DRST's visit code holds eight children: on 16-wide nodes its row is empty, and asking for it says
/// why instead of naming an ISA.
TEST(SceneGeometry, DrstIsRefusedOnSixteenWideNodes) {
    auto geometry = std::make_shared<const SceneGeometry>(quadsAndSpheres(3, 2));
    StructureOptions options;
    options.bvhWidth = 16;
    const auto structure = buildWideBvh(geometry, options);
    EXPECT_FALSE(kernelTable<16>(Isa::Sse42).find("drst")->available());
    EXPECT_TRUE(kernelTable<16>(Isa::Sse42).find("stream")->available());
    try {
        structure->tracer({"drst"});
        ADD_FAILURE() << "drst on a 16-wide BVH must be refused";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("16-wide"), std::string::npos) << e.what();
    }
}

/// Triangles and user primitives share one tree: a scene with both has a root over both subtrees,
/// with the user leaves marked.
TEST(SceneGeometry, OneTreeOverTrianglesAndUserPrimitives) {
    SceneAccel<8> accel(std::make_shared<const SceneGeometry>(quadsAndSpheres(3, 2)));
    const SceneView<8> view = accel.view();
    ASSERT_FALSE(view.root.isLeaf());
    size_t userLeaves = 0, triangleLeaves = 0;
    for (const WideNode<8>& node : accel.bvh().nodes)
        for (NodeRef child : node.child)
            if (child.isLeaf() && child.count() > 0) (child.isUserLeaf() ? userLeaves : triangleLeaves) += 1;
    EXPECT_GE(userLeaves, 1u);
    EXPECT_GE(triangleLeaves, 1u);
}

} // namespace
} // namespace wideray
