// Watertightness: rays through shared edges and vertices of closed meshes never slip through, with
// the reference of every ISA (each has its own arithmetic: FMA where the ISA has it).
#include <gtest/gtest.h>

#include <random>

#include "io/mesh_generators.h"
#include "accel/scene_accel.h"
#include "kernels/kernel_registry.h"

namespace wideray {
namespace {

Ray rayTo(const glm::vec3& from, const glm::vec3& to) {
    glm::vec3 d = to - from;
    return {from.x, from.y, from.z, d.x, d.y, d.z, 0.0f, std::numeric_limits<float>::infinity()};
}

Hit trace(const SceneAccel<8>& accel, const Ray& ray, Isa isa) {
    Hit hit;
    referenceKernel<8>(isa).intersect(accel.view(), &ray, &hit, 1, nullptr);
    return hit;
}

/// Aims rays from interior points at every vertex and at points along every edge.
void expectClosed(const TriangleMesh& mesh, const std::vector<glm::vec3>& insidePoints) {
    SceneAccel<8> accel(std::make_shared<SceneGeometry>(mesh));
    for (Isa isa : supportedIsas()) {
        size_t rays = 0, misses = 0;
        for (const glm::vec3& o : insidePoints) {
            for (const glm::vec3& v : mesh.positions) {
                ++rays;
                misses += !trace(accel, rayTo(o, v), isa).valid();
            }
            for (const glm::uvec3& t : mesh.triangles)
                for (int e = 0; e < 3; ++e) {
                    glm::vec3 a = mesh.positions[t[e]], b = mesh.positions[t[(e + 1) % 3]];
                    for (float s : {0.5f, 0.25f, 1.0f / 3.0f, 0.9f}) {
                        ++rays;
                        misses += !trace(accel, rayTo(o, a + s * (b - a)), isa).valid();
                    }
                }
        }
        EXPECT_EQ(misses, 0u) << "of " << rays << " rays at edges and vertices, " << isaName(isa);
    }
}

TEST(Watertight, IcosphereFromInside) {
    expectClosed(makeIcosphere(3), {{0, 0, 0}, {0.1f, -0.2f, 0.3f}, {-0.5f, 0.25f, 0.125f}});
}

TEST(Watertight, CubeFromInside) {
    expectClosed(makeCube(), {{0, 0, 0}, {0.3f, 0.3f, 0.3f}, {-0.7f, 0.1f, 0.5f}, {0.0f, 0.999f, 0.0f}});
}

TEST(Watertight, TorusFromInsideTheTube) {
    TriangleMesh torus = makeTorus(1.0f, 0.3f, 24, 12);
    expectClosed(torus, {{1.0f, 0.0f, 0.0f}, {0.0f, 0.05f, 1.0f}, {-0.8f, -0.1f, 0.0f}});
}

TEST(Watertight, SharedDiagonalOfAQuadIsNeverMissed) {
    SceneAccel<8> accel(std::make_shared<SceneGeometry>(makeQuad()));
    for (Isa isa : supportedIsas()) {
        SCOPED_TRACE(isaName(isa));
        std::mt19937 rng(7);
        std::uniform_real_distribution<float> coord(-0.999f, 0.999f);
        for (int i = 0; i < 10000; ++i) {
            float x = coord(rng);  // the diagonal x == z is the edge both triangles share
            Ray down{x, 1.0f, x, 0.0f, -1.0f, 0.0f, 0.0f, 10.0f};
            Hit hit = trace(accel, down, isa);
            ASSERT_TRUE(hit.valid()) << "x = z = " << x;
            EXPECT_EQ(hit.t, 1.0f);
            glm::vec3 d = glm::normalize(glm::vec3(0.3f, -1.0f, 0.2f));
            Ray slanted{x - d.x / -d.y, 1.0f, x - d.z / -d.y, d.x, d.y, d.z, 0.0f, 10.0f};
            EXPECT_TRUE(trace(accel, slanted, isa).valid()) << "slanted ray at x = z = " << x;
        }
    }
}

TEST(Watertight, AxisParallelRaysAndZeroDirectionComponents) {
    SceneAccel<8> accel(std::make_shared<SceneGeometry>(makeCube()));
    for (Isa isa : supportedIsas()) {
        SCOPED_TRACE(isaName(isa));
        for (int axis = 0; axis < 3; ++axis)
            for (float sign : {-1.0f, 1.0f}) {
                glm::vec3 d(0.0f), o(0.2f, -0.3f, 0.4f);
                d[axis] = sign;
                o[axis] = -3.0f * sign;
                Hit hit = trace(accel, rayTo(o, o + d), isa);
                ASSERT_TRUE(hit.valid()) << "axis " << axis << " sign " << sign;
                EXPECT_EQ(hit.t, 2.0f) << "axis " << axis << " sign " << sign;
                // Through the cube's edges and corners along an axis.
                glm::vec3 edge(1.0f, 1.0f, 1.0f);
                edge[axis] = -3.0f * sign;
                EXPECT_TRUE(trace(accel, rayTo(edge, edge + d), isa).valid()) << "edge, axis " << axis;
            }
    }
}

TEST(Watertight, GrazingRaysDoNotHitTheInsideOfAPlane) {
    SceneAccel<8> accel(std::make_shared<SceneGeometry>(makeQuad()));
    for (Isa isa : supportedIsas()) {
        SCOPED_TRACE(isaName(isa));
        EXPECT_FALSE(trace(accel, Ray{-2.0f, 1e-6f, 0.1f, 1.0f, 0.0f, 0.0f, 0.0f, 10.0f}, isa).valid());
        EXPECT_FALSE(trace(accel, Ray{-2.0f, -1e-6f, 0.1f, 1.0f, 0.0f, 0.0f, 0.0f, 10.0f}, isa).valid());
        // A ray within the plane sees the triangles edge-on: zero area, no hit, no crash.
        EXPECT_FALSE(trace(accel, Ray{-2.0f, 0.0f, 0.1f, 1.0f, 0.0f, 0.0f, 0.0f, 10.0f}, isa).valid());
        // Nearly grazing but crossing the plane inside the quad does hit.
        glm::vec3 d = glm::normalize(glm::vec3(1.0f, -1e-3f, 0.0f));
        EXPECT_TRUE(trace(accel, Ray{-0.5f, 0.5e-3f, 0.1f, d.x, d.y, d.z, 0.0f, 10.0f}, isa).valid());
    }
}

} // namespace
} // namespace wideray
