// Embree against our scalar reference on the same rays: the same primitive but for a counted budget
// of near-ties. Embree's triangle test is not watertight and does not order equal-t hits, so a ray
// through a shared edge or vertex may go to either neighbour (same t), slip through to whatever lies
// behind, or miss; coplanar overlapping triangles give equal t with another primId.
#include <gtest/gtest.h>

#include <cstdio>

#include <tbb/parallel_for.h>

#include "core/fp_mode.h"
#include "core/mesh_generators.h"
#include "core/mesh_io.h"
#include "core/renderer.h"
#include "core/scene_parser.h"
#include "kernels/embree_tracer.h"
#include "kernels/tracer_factory.h"
#include "ray_sets.h"
#include "test_data.h"

namespace wideray {
namespace {

const std::filesystem::path kSourceDir = WIDERAY_SOURCE_DIR;
constexpr EmbreeKernel kAllKernels[] = {EmbreeKernel::Intersect1, EmbreeKernel::Packet4, EmbreeKernel::Packet8,
                                        EmbreeKernel::Packet16, EmbreeKernel::Stream1M};

struct Traced {
    std::vector<Hit> hits;
    std::vector<uint8_t> occluded;
};

Traced trace(const Tracer& tracer, const std::vector<Ray>& rays) {
    Traced out{std::vector<Hit>(rays.size()), std::vector<uint8_t>(rays.size())};
    tbb::parallel_for(tbb::blocked_range<size_t>(0, rays.size(), 256), [&](const tbb::blocked_range<size_t>& r) {
        std::span<const Ray> batch(rays.data() + r.begin(), r.size());
        tracer.intersect(batch, std::span(out.hits.data() + r.begin(), r.size()), Coherence::Incoherent);
        tracer.occluded(batch, std::span(out.occluded.data() + r.begin(), r.size()), Coherence::Incoherent);
    });
    return out;
}

/// A hit within `eps` (in barycentric units) of an edge of its triangle; spheres have no edges.
bool atEdge(const Hit& h) {
    constexpr float eps = 1e-4f;
    return h.valid() && h.geomId == 0 && std::min({h.u, h.v, 1.0f - h.u - h.v}) <= eps;
}

struct Differences {
    size_t otherPrimitive = 0;  ///< a different (geomId, primId) or a hit on one side only
    size_t equalT = 0;          ///< ... of which both hit within 1e-4 R of each other
    size_t edgeSlip = 0;        ///< ... of which, otherwise, one side hit at an edge or vertex
    size_t unexplained = 0;
    size_t samePrimitiveFarT = 0;  ///< same primitive, but t further apart than 1e-4 R
    size_t occlusion = 0;
    size_t hits = 0;
};

Differences compare(const Traced& ours, const Traced& embree, float radius) {
    Differences d;
    const float tieDistance = 1e-4f * radius;
    for (size_t i = 0; i < ours.hits.size(); ++i) {
        const Hit &a = ours.hits[i], &b = embree.hits[i];
        d.hits += a.valid();
        d.occlusion += ours.occluded[i] != embree.occluded[i];
        if (a.primId == b.primId && a.geomId == b.geomId) {
            if (a.valid() && !(std::abs(a.t - b.t) <= tieDistance) && ++d.samePrimitiveFarT <= 5)
                ADD_FAILURE() << "ray " << i << ": prim " << a.primId << " ours t " << a.t << " (u " << a.u << ", v " << a.v
                              << "), embree t " << b.t << " (u " << b.u << ", v " << b.v << ")";
            continue;
        }
        ++d.otherPrimitive;
        if (a.valid() && b.valid() && std::abs(a.t - b.t) <= tieDistance) {
            ++d.equalT;
            if (d.equalT < 4) std::printf("tie ray %zu: ours %u t %.9g (%g %g) embree %u t %.9g (%g %g)\n", i, a.primId, a.t, a.u, a.v, b.primId, b.t, b.u, b.v);
        }
        else if (atEdge(a) || atEdge(b))
            ++d.edgeSlip;
        else if (++d.unexplained <= 5)
            ADD_FAILURE() << "ray " << i << ": ours prim " << a.primId << " t " << a.t << " (u " << a.u << ", v " << a.v
                          << "), embree prim " << b.primId << " t " << b.t << " (u " << b.u << ", v " << b.v << ")";
    }
    return d;
}

float halfDiagonal(const TriangleMesh& mesh) { return 0.5f * glm::length(testing::meshBounds(mesh).extent()); }

std::unique_ptr<Tracer> referenceTracer(const Scene& scene, const TriangleMesh& world) {
    TracerConfig config;
    config.kernel = KernelChoice::Scalar;
    return buildWiderayTracer(scene, world, config).tracer;
}

/// Every Embree kernel this CPU runs natively against our reference, within the near-tie budget.
void expectEmbreeAgrees(const std::string& name, const Scene& scene, const TriangleMesh& world,
                        const std::vector<Ray>& rays) {
    FlushToZeroScope ftz;
    Traced ours = trace(*referenceTracer(scene, world), rays);
    const size_t budget = rays.size() / 10000;  // 99.99% agreement
    for (EmbreeKernel kernel : kAllKernels) {
        if (!EmbreeTracer::supports(kernel)) {
            std::printf("  %-28s %-15s not native on this CPU, skipped\n", name.c_str(), embreeKernelName(kernel));
            continue;
        }
        EmbreeTracer embree(scene, world, {RTC_BUILD_QUALITY_MEDIUM, kernel, kernel});
        Differences d = compare(ours, trace(embree, rays), halfDiagonal(world));
        std::printf("  %-28s %-15s %zu rays, %zu hits: %zu other primitive (%zu equal t, %zu edge slips, "
                    "%zu unexplained), %zu occlusion differs\n",
                    name.c_str(), embreeKernelName(kernel), rays.size(), d.hits, d.otherPrimitive, d.equalT,
                    d.edgeSlip, d.unexplained, d.occlusion);
        std::fflush(stdout);
        SCOPED_TRACE(name + " " + embreeKernelName(kernel));
        EXPECT_EQ(d.unexplained, 0u);
        EXPECT_LE(d.otherPrimitive, budget);
        EXPECT_LE(d.occlusion, budget);
        EXPECT_EQ(d.samePrimitiveFarT, 0u);
        EXPECT_GT(d.hits, rays.size() / 3) << "the ray set should mostly hit";
    }
}

void expectEmbreeAgreesOnMesh(const std::string& name, const TriangleMesh& mesh, size_t rayCount, uint32_t seed) {
    expectEmbreeAgrees(name, Scene{}, mesh, testing::randomRays(mesh, rayCount, seed));
}

TEST(EmbreeCrosscheck, GeneratedMeshes) {
    expectEmbreeAgreesOnMesh("icosphere(5)", makeIcosphere(5), 50000, 11);
    expectEmbreeAgreesOnMesh("torus(128x64)", makeTorus(1.0f, 0.3f, 128, 64), 50000, 12);
    expectEmbreeAgreesOnMesh("cube", makeCube(), 50000, 13);
}

class EmbreeCrosscheckShared : public ::testing::TestWithParam<const char*> {};

TEST_P(EmbreeCrosscheckShared, AgreesWithReference) {
    auto dir = sharedScenesDir();
    if (!dir) GTEST_SKIP() << "needs ../shared/scenes (or WIDERAY_SCENES)";
    TriangleMesh mesh = loadMesh(*dir / GetParam());
    expectEmbreeAgreesOnMesh(std::filesystem::path(GetParam()).filename().string(), mesh, 30000, 14);
}

INSTANTIATE_TEST_SUITE_P(EmbreeRealMeshes, EmbreeCrosscheckShared,
                         ::testing::Values("cornell-box/CornellBox-Original.obj", "suzanne/suzanne.obj",
                                           "teapot/teapot.obj", "stanford-bunny/bun_zipper.ply",
                                           "stanford-dragon-100k/dragon_100k.ply",
                                           "bitterli-coffee-maker/coffee_maker_merged.ply",
                                           "crytek-sponza/sponza.obj",
                                           "bitterli-country-kitchen/country_kitchen_merged.ply"));

/// The default scene's sphere goes through Embree's user geometry callbacks; half the rays aim at it.
TEST(EmbreeCrosscheck, UserGeometryMatchesOurs) {
    Scene scene = loadScene(kSourceDir / "scenes/default.json");
    ASSERT_FALSE(scene.spheres.empty());
    TriangleMesh world = flattenTriangles(scene);
    std::vector<Ray> rays = testing::randomRays(world, 20000, 15);
    const Sphere& sphere = scene.spheres[0];
    for (size_t i = 0; i < rays.size(); i += 2) {
        glm::vec3 o(rays[i].ox, rays[i].oy, rays[i].oz);
        glm::vec3 target = sphere.center + 0.9f * sphere.radius * glm::vec3(rays[i].dx, rays[i].dy, rays[i].dz);
        glm::vec3 d = glm::normalize(target - o);
        rays[i].dx = d.x, rays[i].dy = d.y, rays[i].dz = d.z;
    }
    expectEmbreeAgrees("default.json", scene, world, rays);

    FlushToZeroScope ftz;
    Traced ours = trace(*referenceTracer(scene, world), rays);
    Traced embree = trace(EmbreeTracer(scene, world), rays);
    size_t sphereHits = 0;
    for (size_t i = 0; i < rays.size(); ++i) {
        if (ours.hits[i].geomId != 1) continue;
        ++sphereHits;
        EXPECT_EQ(embree.hits[i].geomId, 1u) << "ray " << i;
        EXPECT_EQ(embree.hits[i].t, ours.hits[i].t) << "ray " << i;
    }
    EXPECT_GT(sphereHits, rays.size() / 10);
}

TEST(EmbreeCrosscheck, InvalidRaysMissAndAreNotOccluded) {
    const float inf = std::numeric_limits<float>::infinity(), nan = std::numeric_limits<float>::quiet_NaN();
    std::vector<Ray> rays = {
        {0, 0, -5, nan, 0, 1, 0, inf}, {0, 0, -5, 0, 0, inf, 0, inf}, {nan, 0, -5, 0, 0, 1, 0, inf},
        {0, 0, -5, 0, 0, 0, 0, inf},   {0, 0, -5, 0, 0, 1, 10, 1},    {0, 0, -5, 0, 0, 1, nan, inf},
        {0, 0, -5, 0, 0, 1, 0, inf},  // valid, hits: keeps the packets' valid lanes honest
    };
    TriangleMesh mesh = makeIcosphere(2);
    for (EmbreeKernel kernel : kAllKernels) {
        if (!EmbreeTracer::supports(kernel)) continue;
        Traced traced = trace(EmbreeTracer(Scene{}, mesh, {RTC_BUILD_QUALITY_MEDIUM, kernel, kernel}), rays);
        for (size_t i = 0; i + 1 < rays.size(); ++i) {
            EXPECT_FALSE(traced.hits[i].valid()) << embreeKernelName(kernel) << " ray " << i;
            EXPECT_EQ(traced.occluded[i], 0) << embreeKernelName(kernel) << " ray " << i;
        }
        EXPECT_TRUE(traced.hits.back().valid()) << embreeKernelName(kernel);
        EXPECT_EQ(traced.occluded.back(), 1) << embreeKernelName(kernel);
    }
}

Image renderDefaultScene(const Tracer& tracer, const Scene& scene, const TriangleMesh& world) {
    RenderOptions options;
    options.width = 160;
    options.height = 120;
    RenderStats stats;
    return render(scene, world, tracer, options, stats);
}

TEST(EmbreeCrosscheck, DefaultSceneRendersAlike) {
    FlushToZeroScope ftz;
    Scene scene = loadScene(kSourceDir / "scenes/default.json");
    TriangleMesh world = flattenTriangles(scene);
    Image ours = renderDefaultScene(*referenceTracer(scene, world), scene, world);
    EmbreeTracer embree(scene, world);
    Image theirs = renderDefaultScene(embree, scene, world);
    ASSERT_EQ(ours.pixels.size(), theirs.pixels.size());
    double sum = 0, largest = 0;
    size_t differing = 0;
    for (size_t i = 0; i < ours.pixels.size(); ++i) {
        double d = std::abs(double(ours.pixels[i]) - double(theirs.pixels[i]));
        sum += d;
        largest = std::max(largest, d);
        differing += d > 0.02;
    }
    double mean = sum / double(ours.pixels.size());
    std::printf("  default.json 160x120 through %s: mean |difference| %.6f, max %.4f, %zu of %zu values differ "
                "by more than 0.02\n",
                embree.description().c_str(), mean, largest, differing, ours.pixels.size());
    EXPECT_LT(mean, 0.002);
    EXPECT_LT(differing, ours.pixels.size() / 200);
}

} // namespace
} // namespace wideray
