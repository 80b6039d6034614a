// Embree against our scalar reference on the same rays: the same primitive but for a counted budget
// of near-ties. Embree's triangle test is not watertight and does not order equal-t hits, so a ray
// through a shared edge or vertex may go to either neighbour (same t), slip through to whatever lies
// behind, or miss; coplanar overlapping triangles give equal t with another primId.
#include <gtest/gtest.h>

#include <cstdio>

#include <tbb/parallel_for.h>

#include "core/fp_mode.h"
#include "io/mesh_generators.h"
#include "io/mesh_io.h"
#include "render/renderer.h"
#include "io/scene_parser.h"
#include "backends/embree_tracer.h"
#include "backends/wideray_structure.h"
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

Traced trace(const Tracer& tracer, const std::vector<Ray>& rays, Coherence coherence = Coherence::Incoherent) {
    Traced out{std::vector<Hit>(rays.size()), std::vector<uint8_t>(rays.size())};
    tbb::parallel_for(tbb::blocked_range<size_t>(0, rays.size(), 256), [&](const tbb::blocked_range<size_t>& r) {
        std::span<const Ray> batch(rays.data() + r.begin(), r.size());
        tracer.intersect(batch, std::span(out.hits.data() + r.begin(), r.size()), coherence);
        tracer.occluded(batch, std::span(out.occluded.data() + r.begin(), r.size()), coherence);
    });
    return out;
}

/// A hit within `eps` (in barycentric units) of an edge of its triangle; spheres have no edges.
bool atEdge(const Hit& h) {
    constexpr float eps = 1e-4f;
    return h.valid() && h.geomId == 0 && std::min({h.u, h.v, 1.0f - h.u - h.v}) <= eps;
}

/// |cos| of the angle between the ray and the triangle's plane normal; t is ill-conditioned near 0.
float incidence(const TriangleMesh& world, const Ray& ray, uint32_t primId) {
    const glm::uvec3& tri = world.triangles[primId];
    glm::vec3 n = glm::cross(world.positions[tri.y] - world.positions[tri.x], world.positions[tri.z] - world.positions[tri.x]);
    glm::vec3 d(ray.dx, ray.dy, ray.dz);
    return std::abs(glm::dot(n, d)) / (glm::length(n) * glm::length(d));
}

struct Differences {
    size_t hits = 0;
    size_t otherPrimitive = 0;   ///< a different (geomId, primId), or a hit on one side only; of these:
    size_t sharedEdge = 0;       ///<   both hit within 1e-4 R, one at an edge or vertex of its triangle
    size_t overlap = 0;          ///<   both hit within 1e-4 R inside their triangles: coplanar overlap
    size_t edgeSlip = 0;         ///<   t apart, one side hit at an edge or vertex the other slipped through
    size_t unexplained = 0;
    size_t grazing = 0;          ///< same primitive, t apart by more than 1e-4 R at grazing incidence
    size_t samePrimitiveFarT = 0;  ///< same primitive, t apart by more than 1e-4 R otherwise
    size_t occlusion = 0;
};

Differences compare(const TriangleMesh& world, const std::vector<Ray>& rays, const Traced& ours,
                    const Traced& embree) {
    Differences d;
    const float tieDistance = 1e-4f * 0.5f * glm::length(testing::meshBounds(world).extent());
    for (size_t i = 0; i < rays.size(); ++i) {
        const Hit &a = ours.hits[i], &b = embree.hits[i];
        d.hits += a.valid();
        d.occlusion += ours.occluded[i] != embree.occluded[i];
        bool closeT = a.valid() && b.valid() && std::abs(a.t - b.t) <= tieDistance;
        if (a.primId == b.primId && a.geomId == b.geomId) {
            if (!a.valid() || closeT) continue;
            if (a.geomId == 0 && incidence(world, rays[i], a.primId) < 1e-2f)
                ++d.grazing;
            else if (++d.samePrimitiveFarT <= 5)
                ADD_FAILURE() << "ray " << i << ": prim " << a.primId << " ours t " << a.t << ", embree t " << b.t;
            continue;
        }
        ++d.otherPrimitive;
        if (closeT && (atEdge(a) || atEdge(b)))
            ++d.sharedEdge;
        else if (closeT)
            ++d.overlap;
        else if (atEdge(a) || atEdge(b))
            ++d.edgeSlip;
        else if (++d.unexplained <= 5)
            ADD_FAILURE() << "ray " << i << ": ours prim " << a.primId << " t " << a.t << " (u " << a.u << ", v " << a.v
                          << "), embree prim " << b.primId << " t " << b.t << " (u " << b.u << ", v " << b.v << ")";
    }
    return d;
}

std::unique_ptr<Tracer> referenceTracer(std::shared_ptr<const SceneGeometry> geometry) {
    return buildWideBvh(std::move(geometry), {})->tracer({"scalar"});
}

std::shared_ptr<const EmbreeStructure> embreeMedium(std::shared_ptr<const SceneGeometry> geometry) {
    return std::make_shared<const EmbreeStructure>(std::move(geometry), RTC_BUILD_QUALITY_MEDIUM);
}

/// Every Embree kernel this CPU runs natively against our reference, within the near-tie budget.
void expectEmbreeAgrees(const std::string& name, std::shared_ptr<const SceneGeometry> geometry,
                        const std::vector<Ray>& rays) {
    FlushToZeroScope ftz;
    const TriangleMesh& world = *(*geometry)[0].triangles();
    Traced ours = trace(*referenceTracer(geometry), rays);
    std::shared_ptr<const EmbreeStructure> structure = embreeMedium(geometry);
    const size_t budget = rays.size() / 10000;  // 99.99% agreement
    for (EmbreeKernel kernel : kAllKernels) {
        if (!embreeSupports(kernel)) {
            std::printf("  %-28s %-15s not native on this CPU, skipped\n", name.c_str(), embreeKernelName(kernel));
            continue;
        }
        EmbreeTracer embree(structure, kernel, kernel);
        // Packets also run with Embree's coherent-ray hint, the way the renderer calls them.
        bool packet = kernel != EmbreeKernel::Intersect1 && kernel != EmbreeKernel::Stream1M;
        Differences d = compare(world, rays, ours, trace(embree, rays, packet ? Coherence::Coherent : Coherence::Incoherent));
        std::printf("  %-26s %-14s %zu rays, %zu hits: %zu other primitive (%zu shared edge, %zu coplanar "
                    "overlap, %zu edge slip, %zu unexplained), %zu grazing t, %zu occlusion differs; build %.1f ms, "
                    "%.2f MB\n",
                    name.c_str(), embreeKernelName(kernel), rays.size(), d.hits, d.otherPrimitive, d.sharedEdge,
                    d.overlap, d.edgeSlip, d.unexplained, d.grazing, d.occlusion, structure->buildSeconds() * 1e3,
                    double(structure->bytes()) / (1 << 20));
        std::fflush(stdout);
        SCOPED_TRACE(name + " " + embreeKernelName(kernel));
        EXPECT_EQ(d.unexplained, 0u);
        EXPECT_EQ(d.samePrimitiveFarT, 0u);
        // Coplanar overlaps have no right answer that Embree could know (each engine's rounding picks
        // one), so they are counted but left out of the 99.99% budget.
        EXPECT_LE(d.otherPrimitive - d.overlap + d.grazing, budget);
        EXPECT_LE(d.occlusion, budget);
        EXPECT_GT(d.hits, rays.size() / 3) << "the ray set should mostly hit";
    }
}

void expectEmbreeAgreesOnMesh(const std::string& name, const TriangleMesh& mesh, size_t rayCount, uint32_t seed) {
    expectEmbreeAgrees(name, std::make_shared<const SceneGeometry>(mesh), testing::randomRays(mesh, rayCount, seed));
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
                         ::testing::ValuesIn(kSharedMeshes));

/// The default scene's sphere goes through Embree's user geometry callbacks; half the rays aim at it.
TEST(EmbreeCrosscheck, UserGeometryMatchesOurs) {
    SceneDescription scene = loadScene(kSourceDir / "scenes/default.json");
    ASSERT_FALSE(scene.spheres.empty());
    auto geometry = std::make_shared<const SceneGeometry>(scene);
    std::vector<Ray> rays = testing::randomRays(*(*geometry)[0].triangles(), 20000, 15);
    const Sphere& sphere = scene.spheres[0];
    for (size_t i = 0; i < rays.size(); i += 2) {
        glm::vec3 o(rays[i].ox, rays[i].oy, rays[i].oz);
        glm::vec3 target = sphere.center + 0.9f * sphere.radius * glm::vec3(rays[i].dx, rays[i].dy, rays[i].dz);
        glm::vec3 d = glm::normalize(target - o);
        rays[i].dx = d.x, rays[i].dy = d.y, rays[i].dz = d.z;
    }
    expectEmbreeAgrees("default.json", geometry, rays);

    FlushToZeroScope ftz;
    Traced ours = trace(*referenceTracer(geometry), rays);
    Traced embree = trace(*embreeMedium(geometry)->tracer({}), rays);
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
    std::shared_ptr<const EmbreeStructure> structure = embreeMedium(std::make_shared<const SceneGeometry>(makeIcosphere(2)));
    for (EmbreeKernel kernel : kAllKernels) {
        if (!embreeSupports(kernel)) continue;
        Traced traced = trace(EmbreeTracer(structure, kernel, kernel), rays);
        for (size_t i = 0; i + 1 < rays.size(); ++i) {
            EXPECT_FALSE(traced.hits[i].valid()) << embreeKernelName(kernel) << " ray " << i;
            EXPECT_EQ(traced.occluded[i], 0) << embreeKernelName(kernel) << " ray " << i;
        }
        EXPECT_TRUE(traced.hits.back().valid()) << embreeKernelName(kernel);
        EXPECT_EQ(traced.occluded.back(), 1) << embreeKernelName(kernel);
    }
}

Image renderDefaultScene(const Tracer& tracer, const SceneDescription& scene) {
    RenderOptions options;
    options.width = 160;
    options.height = 120;
    RenderStats stats;
    return render(scene, tracer, options, stats);
}

TEST(EmbreeCrosscheck, DefaultSceneRendersAlike) {
    FlushToZeroScope ftz;
    SceneDescription scene = loadScene(kSourceDir / "scenes/default.json");
    auto geometry = std::make_shared<const SceneGeometry>(scene);
    Image ours = renderDefaultScene(*referenceTracer(geometry), scene);
    std::unique_ptr<Tracer> embree = embreeMedium(geometry)->tracer({});
    Image theirs = renderDefaultScene(*embree, scene);
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
                embree->description().c_str(), mean, largest, differing, ours.pixels.size());
    EXPECT_LT(mean, 0.002);
    EXPECT_LT(differing, ours.pixels.size() / 200);
}

} // namespace
} // namespace wideray
