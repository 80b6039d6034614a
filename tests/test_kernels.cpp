// Every kernel (single, packet4/8/16, stream; every ISA this CPU has; N = 4 and 8) returns exactly
// the hits of the scalar reference: the same primitive and the same t, bit for bit, and the same
// occlusion.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <random>

#include "render/bench_rays.h"
#include "core/fp_mode.h"
#include "io/mesh_framing.h"
#include "io/mesh_generators.h"
#include "io/mesh_io.h"
#include "accel/scene_accel.h"
#include "kernels/kernel_registry.h"
#include "geometry/triangle_geometry.h"
#include "instanced_scene.h"
#include "ray_sets.h"
#include "test_data.h"

namespace wideray {
namespace {

/// From each primary hit toward the scene's first light (like the renderer's shadow rays).
template <int N>
std::vector<Ray> shadowRays(const SceneAccel<N>& accel, const std::vector<Ray>& primary, const glm::vec3& light) {
    std::vector<Hit> hits(primary.size());
    referenceKernel<N>(Isa::Sse42).intersect(accel.view(), primary.data(), hits.data(), primary.size(), nullptr);
    std::vector<Ray> rays;
    for (size_t i = 0; i < primary.size(); ++i) {
        if (!hits[i].valid()) continue;
        const Ray& r = primary[i];
        glm::vec3 p = glm::vec3(r.ox, r.oy, r.oz) + hits[i].t * glm::vec3(r.dx, r.dy, r.dz);
        glm::vec3 d = light - p;
        float dist = glm::length(d);
        d /= dist;
        rays.push_back({p.x, p.y, p.z, d.x, d.y, d.z, 1e-4f * dist, dist});
    }
    return rays;
}

/// Every kernel of the table that its ISA runs, but the reference itself.
template <int N>
std::vector<Kernel<N>> kernelsOf(const KernelTable<N>& t) {
    std::vector<Kernel<N>> all;
    for (const Kernel<N>& k : t.rows)
        if (k.available() && std::string_view(k.name) != "scalar") all.push_back(k);
    return all;
}

/// The torus the generated-mesh tests trace (one instance of it, no camera or light set).
SceneDescription torusScene() {
    SceneDescription scene;
    scene.meshes = {makeTorus(1.0f, 0.3f, 96, 48)};
    scene.instances.push_back({});
    return scene;
}

/// The work per ray of a kernel's closest-hit traversal of `rays`.
std::vector<TraversalCost> closestHitCosts(const Kernel<8>& kernel, const SceneAccel<8>& accel,
                                           const std::vector<Ray>& rays) {
    std::vector<Hit> hits(rays.size());
    std::vector<TraversalCost> costs(rays.size());
    kernel.intersect(accel.view(), rays.data(), hits.data(), rays.size(), costs.data());
    return costs;
}

template <int N>
void expectAllKernelsMatchReference(const SceneAccel<N>& accel, const std::vector<Ray>& rays, const char* what) {
    for (Isa isa : supportedIsas()) {
        std::vector<Hit> expected(rays.size());
        std::vector<uint8_t> expectedOccluded(rays.size());
        referenceKernel<N>(isa).intersect(accel.view(), rays.data(), expected.data(), rays.size(), nullptr);
        referenceKernel<N>(isa).occluded(accel.view(), rays.data(), expectedOccluded.data(), rays.size(), nullptr);
        for (const Kernel<N>& kernel : kernelsOf(kernelTable<N>(isa))) {
            // Guard entries past the rays' answers, which no kernel may write.
            constexpr size_t kGuard = 16;
            const Hit guardHit{-1.0f, 2.0f, 3.0f, 123u, 456u};
            std::vector<Hit> hits(rays.size() + kGuard, guardHit);
            std::vector<uint8_t> occluded(rays.size() + kGuard, 7);
            kernel.intersect(accel.view(), rays.data(), hits.data(), rays.size(), nullptr);
            kernel.occluded(accel.view(), rays.data(), occluded.data(), rays.size(), nullptr);
            for (size_t i = rays.size(); i < rays.size() + kGuard; ++i) {
                EXPECT_TRUE(std::memcmp(&hits[i], &guardHit, sizeof(Hit)) == 0 && occluded[i] == 7)
                    << what << " " << kernel.name << " " << isaName(isa) << " N=" << N << " wrote past its " << rays.size()
                    << " rays, at " << i;
            }
            size_t hitMismatches = 0, occlusionMismatches = 0;
            for (size_t i = 0; i < rays.size(); ++i) {
                const Hit &a = hits[i], &b = expected[i];
                bool same = a.primId == b.primId && a.geomId == b.geomId &&
                            std::memcmp(&a.t, &b.t, 4) == 0 && std::memcmp(&a.u, &b.u, 4) == 0 &&
                            std::memcmp(&a.v, &b.v, 4) == 0;
                if (!same && ++hitMismatches <= 3)
                    ADD_FAILURE() << what << " " << kernel.name << " " << isaName(isa) << " N=" << N << " ray " << i
                                  << ": prim " << a.primId << " t " << a.t << " vs reference prim " << b.primId
                                  << " t " << b.t;
                occlusionMismatches += occluded[i] != expectedOccluded[i];
            }
            EXPECT_EQ(hitMismatches, 0u) << what << " " << kernel.name << " " << isaName(isa) << " N=" << N;
            EXPECT_EQ(occlusionMismatches, 0u) << what << " " << kernel.name << " " << isaName(isa) << " N=" << N;
            if (kernel.occludedCached) {
                ShadowCache cache;
                std::vector<uint8_t> cached(rays.size(), 7);
                kernel.occludedCached(accel.view(), rays.data(), cached.data(), rays.size(), cache);
                EXPECT_TRUE(cached == expectedOccluded) << what << " shadow cache " << isaName(isa) << " N=" << N;
                EXPECT_LE(cache.hits, cache.queries);
            }
        }
    }
}

/// How far the references of two ISAs may disagree on t, in units of 2^-23 * reach / |cos| (see
/// isaDistanceBound); measured at most 8.2 (random rays in Sponza), 2.8 on camera rays.
constexpr double kIsaDistanceUlps = 16.0;

/// The ISAs' references round the shear and T differently (FMA on AVX2 and AVX-512, not on SSE4.2).
/// t = T / det is a mean of the vertices' sheared depths weighted by U, V and W, each rounded relative
/// to the vertices' distance from the origin (the reach, in units of t), and the weights' errors grow as
/// 1 / |cos| of the incidence angle (det is the triangle's projected area): |delta t| is bounded by a few
/// ulps of the reach over |cos|.
double isaDistanceBound(const TriangleMesh& mesh, const Ray& ray, uint32_t prim) {
    const glm::uvec3& tri = mesh.triangles[prim];
    const glm::vec3 &a = mesh.positions[tri.x], &b = mesh.positions[tri.y], &c = mesh.positions[tri.z];
    const glm::vec3 o(ray.ox, ray.oy, ray.oz), d(ray.dx, ray.dy, ray.dz);
    const double reach = std::max({glm::length(a - o), glm::length(b - o), glm::length(c - o)}) / glm::length(d);
    const double cosine = std::abs(glm::dot(glm::normalize(glm::cross(b - a, c - a)), glm::normalize(d)));
    return kIsaDistanceUlps * 0x1p-23 * reach / std::max(cosine, 1e-6);
}

/// Every ISA's reference against the baseline's: the same primitive and t within isaDistanceBound,
/// or, where two triangles are tied within that bound (a corner, coplanar duplicates), either of them.
template <int N>
void expectIsasAgree(const SceneAccel<N>& accel, const TriangleMesh& mesh, const std::vector<Ray>& rays,
                     const char* what) {
    std::vector<Hit> baseline(rays.size());
    referenceKernel<N>(Isa::Sse42).intersect(accel.view(), rays.data(), baseline.data(), rays.size(), nullptr);
    for (Isa isa : supportedIsas()) {
        if (isa == Isa::Sse42) continue;
        std::vector<Hit> hits(rays.size());
        referenceKernel<N>(isa).intersect(accel.view(), rays.data(), hits.data(), rays.size(), nullptr);
        size_t ties = 0, disagreements = 0;
        for (size_t i = 0; i < rays.size(); ++i) {
            const Hit &a = hits[i], &b = baseline[i];
            bool agree = a.valid() == b.valid() && a.geomId == b.geomId;
            if (agree && a.valid() && a.geomId == 0) {
                double bound = isaDistanceBound(mesh, rays[i], b.primId);
                if (a.primId != b.primId) {
                    bound = std::max(bound, isaDistanceBound(mesh, rays[i], a.primId));
                    ++ties;
                }
                agree = std::abs(double(a.t) - double(b.t)) <= bound;
            } else if (agree && a.valid()) {
                agree = a.primId == b.primId && a.t == b.t;  // user primitives run baseline code everywhere
            }
            if (!agree && ++disagreements <= 3)
                ADD_FAILURE() << what << " " << isaName(isa) << " ray " << i << ": geom " << a.geomId << " prim "
                              << a.primId << " t " << a.t << " vs baseline geom " << b.geomId << " prim " << b.primId
                              << " t " << b.t;
        }
        EXPECT_EQ(disagreements, 0u) << what << " " << isaName(isa) << " N=" << N;
        EXPECT_LE(ties, rays.size() / 50) << what << " " << isaName(isa) << ": ties are rare";
    }
}

template <int N>
void checkScene(const SceneDescription& scene, int size) {
    FlushToZeroScope ftz;
    auto geometry = std::make_shared<const SceneGeometry>(scene);
    const TriangleMesh& world = *(*geometry)[0].triangles();
    SceneAccel<N> accel(geometry);
    std::vector<Ray> primary = primaryRays(scene, size, size);
    const std::vector<Ray> shadow = shadowRays(accel, primary, scene.lights.at(0).position);
    expectAllKernelsMatchReference(accel, primary, "primary");
    expectAllKernelsMatchReference(accel, shadow, "shadow");
    expectIsasAgree(accel, world, primary, "primary");
    if (!world.triangles.empty()) {
        const std::vector<Ray> random = testing::randomRays(world, size_t(size) * size / 4, 11);
        expectAllKernelsMatchReference(accel, random, "random");
        expectIsasAgree(accel, world, random, "random");
        // Incoherent packets whose rays nearly all hit part singly (IncoherentPackets): all of these
        // rays hit; of the random rays above, 27-40% miss, so their packets after the first few stay
        // whole.
        const std::vector<Ray> aimed = testing::randomRays(world, size_t(size) * size / 4, 12, true);
        expectAllKernelsMatchReference(accel, aimed, "aimed");
    }
}

TEST(Kernels, MatchReferenceOnDefaultScene) {
    SceneDescription scene = loadSceneOrMesh(std::filesystem::path(WIDERAY_SOURCE_DIR) / "scenes/default.json");
    checkScene<4>(scene, 128);
    checkScene<8>(scene, 128);
    checkScene<16>(scene, 128);
}

TEST(Kernels, MatchReferenceOnGeneratedMeshes) {
    SceneDescription scene = torusScene();
    scene.camera.position = {0.5f, 2.0f, 3.0f};
    scene.lights.push_back({});
    scene.lights[0].position = {1.0f, 3.0f, 1.0f};
    scene.materials.push_back({});
    checkScene<4>(scene, 96);
    checkScene<8>(scene, 96);
    checkScene<16>(scene, 96);
}

TEST(Kernels, MatchReferenceThroughTwoLevelInstances) {
    // The instance leaves trace their meshes with the ISA's single-ray kernel whatever kernel reached
    // them: every kernel, packets and streams included, returns the reference's hits bit for bit.
    FlushToZeroScope ftz;
    const SceneDescription scene = testing::instancedScene();
    auto geometry = std::make_shared<const SceneGeometry>(scene, Instancing::TwoLevel);
    ASSERT_NE(geometry->instances(), nullptr);
    const TriangleMesh flattened = flattenTriangles(scene);
    const std::vector<Ray> primary = primaryRays(scene, 96, 96), random = testing::randomRays(flattened, 4096, 3);
    auto check = [&](const auto& accel) {
        expectAllKernelsMatchReference(accel, primary, "instances, primary");
        expectAllKernelsMatchReference(accel, shadowRays(accel, primary, scene.lights[0].position), "instances, shadow");
        expectAllKernelsMatchReference(accel, random, "instances, random");
    };
    check(SceneAccel<4>(geometry));
    check(SceneAccel<8>(geometry));
    check(SceneAccel<16>(geometry));
}

class SharedMeshKernels : public ::testing::TestWithParam<const char*> {};

TEST_P(SharedMeshKernels, MatchReference) {
    auto dir = sharedScenesDir();
    if (!dir) GTEST_SKIP() << "needs ../shared/scenes (or WIDERAY_SCENES)";
#ifdef WIDERAY_SANITIZE
    const int size = 64;
#else
    const int size = 256;
#endif
    SceneDescription scene = sceneFromMesh(*dir / GetParam(), size, size);
    scene.lights[0].position = scene.camera.position + (scene.lights[0].position - scene.camera.position) * 0.5f;
    checkScene<8>(scene, size);
    checkScene<4>(scene, size / 2);
    checkScene<16>(scene, size / 2);
}

INSTANTIATE_TEST_SUITE_P(RealMeshes, SharedMeshKernels,
                         ::testing::Values("teapot/teapot.obj", "stanford-bunny/bun_zipper.ply",
                                           "crytek-sponza/sponza.obj",
                                           "bitterli-country-kitchen/country_kitchen_merged.ply"));

TEST(Kernels, ShadowCacheAnswersRepeatedOccluders) {
    FlushToZeroScope ftz;
    TriangleMesh mesh = makeQuad();  // one block, x and z in [-1, 1], between the origins and the light
    SceneAccel<8> accel(std::make_shared<SceneGeometry>(mesh));
    std::vector<Ray> rays;  // a third of them pass beside the quad, in the same packets as rays it blocks
    for (int i = 0; i < 1024; ++i)
        rays.push_back({-1.4951f + 0.0938f * float(i % 32), -1.0f, -0.4953f + 0.0312f * float(i / 32), 0.0f, 1.0f, 0.0f,
                        0.0f, 2.0f});
    for (Isa isa : supportedIsas()) {
        std::vector<uint8_t> expected(rays.size());
        referenceKernel<8>(isa).occluded(accel.view(), rays.data(), expected.data(), rays.size(), nullptr);
        const size_t blocked = size_t(std::count(expected.begin(), expected.end(), 1));
        ASSERT_GT(blocked, rays.size() / 2);
        ASSERT_LT(blocked, rays.size());
        for (const Kernel<8>& kernel : kernelsOf(kernelTable<8>(isa))) {
            if (!kernel.occludedCached) continue;
            // In batches of 256 rays, as a renderer's tiles call it, one cache for all.
            ShadowCache cache;
            std::vector<uint8_t> occluded(rays.size(), 7);
            for (size_t first = 0; first < rays.size(); first += 256)
                kernel.occludedCached(accel.view(), rays.data() + first, occluded.data() + first, 256, cache);
            EXPECT_TRUE(occluded == expected) << kernel.name << " " << isaName(isa);
            EXPECT_EQ(cache.queries, rays.size()) << kernel.name << " " << isaName(isa);
            // Once the quad's block is cached, it answers the rays it blocks (packets drop it where it
            // blocks none of their rays, and the next traversal that meets the quad caches it again).
            EXPECT_GE(cache.hits + 256, blocked) << kernel.name << " " << isaName(isa);
        }
    }
}

TEST(Kernels, ShadowCacheKeepsTheLatestOccludersFirst) {
    static_assert(ShadowCache::kBlocks == 2, "the expectations below are for two entries");
    auto entries = [](const ShadowCache& c) { return std::vector<uint32_t>(c.blocks, c.blocks + ShadowCache::kBlocks); };
    const uint32_t empty = ShadowCache::kEmpty;
    ShadowCache cache;
    cache.remember();  // no traversal found an occluder
    EXPECT_EQ(entries(cache), (std::vector<uint32_t>{empty, empty}));
    cache.found = 5, cache.remember();
    cache.found = 7, cache.remember();
    EXPECT_EQ(entries(cache), (std::vector<uint32_t>{7, 5}));
    EXPECT_EQ(cache.found, empty);
    cache.found = 5, cache.remember();  // already cached: moves first, nothing is lost
    EXPECT_EQ(entries(cache), (std::vector<uint32_t>{5, 7}));
    cache.found = 9, cache.remember();  // the oldest goes
    EXPECT_EQ(entries(cache), (std::vector<uint32_t>{9, 5}));
    cache.promote(1);
    EXPECT_EQ(entries(cache), (std::vector<uint32_t>{5, 9}));
    cache.forget(0);
    EXPECT_EQ(entries(cache), (std::vector<uint32_t>{9, empty}));
}

TEST(Kernels, EdgeCases) {
    FlushToZeroScope ftz;
    TriangleMesh mesh = makeIcosphere(3);
    SceneAccel<8> accel(std::make_shared<SceneGeometry>(mesh));
    const float inf = std::numeric_limits<float>::infinity(), nan = std::numeric_limits<float>::quiet_NaN();
    std::vector<Ray> rays = testing::randomRays(mesh, 4097, 5);
    // Invalid rays scattered through packets: NaN/Inf directions and origins, tnear > tfar, zero direction.
    for (size_t i = 0; i < rays.size(); i += 7) {
        switch ((i / 7) % 6) {
        case 0: rays[i].dx = nan; break;
        case 1: rays[i].dy = inf; break;
        case 2: rays[i].ox = -inf; break;
        case 3: rays[i].tnear = 5.0f; rays[i].tfar = 1.0f; break;
        case 4: rays[i].dx = rays[i].dy = rays[i].dz = 0.0f; break;
        case 5: rays[i].tfar = nan; break;
        }
    }
    expectAllKernelsMatchReference(accel, rays, "edge cases (4097 rays)");
    for (size_t count : {size_t(1), size_t(3), size_t(17)}) {
        std::vector<Ray> few(rays.begin() + 1, rays.begin() + 1 + count);
        expectAllKernelsMatchReference(accel, few, "few rays");
    }
}

/// Every field on its own makes a ray invalid (the kernels' test of all fields at once).
TEST(Kernels, InvalidRaysAreFoundFieldByField) {
    const float inf = std::numeric_limits<float>::infinity(), nan = std::numeric_limits<float>::quiet_NaN();
    const Ray good{1.0f, -2.0f, 3.0f, 0.0f, 0.0f, -1.0f, 0.0f, inf};
    EXPECT_TRUE(isValidRay(good));
    float Ray::*directions[] = {&Ray::ox, &Ray::oy, &Ray::oz, &Ray::dx, &Ray::dy, &Ray::dz};
    for (float Ray::*field : directions)
        for (float bad : {nan, inf, -inf}) {
            Ray r = good;
            r.*field = bad;
            EXPECT_FALSE(isValidRay(r)) << "field " << (&(r.*field) - &r.ox) << " = " << bad;
        }
    for (float Ray::*axis : {&Ray::dx, &Ray::dy, &Ray::dz}) {
        Ray r = good;
        r.dx = r.dy = r.dz = 0.0f;
        EXPECT_FALSE(isValidRay(r)) << "zero direction";
        r.*axis = -0x1p-100f;
        EXPECT_TRUE(isValidRay(r)) << "direction along axis " << (&(r.*axis) - &r.dx);
    }
    Ray r = good;
    r.tnear = 2.0f, r.tfar = 1.0f;
    EXPECT_FALSE(isValidRay(r)) << "tnear > tfar";
    r.tnear = r.tfar = 1.0f;
    EXPECT_TRUE(isValidRay(r)) << "tnear == tfar";
    r.tnear = -inf;
    EXPECT_TRUE(isValidRay(r)) << "tnear = -inf";
    r.tnear = r.tfar = inf;
    EXPECT_FALSE(isValidRay(r)) << "tnear = inf";
    for (float Ray::*limit : {&Ray::tnear, &Ray::tfar}) {
        r = good;
        r.*limit = nan;
        EXPECT_FALSE(isValidRay(r)) << "NaN interval";
    }
}

} // namespace
} // namespace wideray

namespace wideray {
namespace {

/// The cost AOV counts the chosen kernel's own work: every kernel fills per-ray costs without
/// changing its hits (or its occlusion answers), the single-ray kernels agree with each other, and the packet and stream
/// kernels (which visit nodes for groups of rays) report work of their own.
TEST(Kernels, CostsMeasureTheChosenKernel) {
    FlushToZeroScope ftz;
    SceneDescription scene = loadSceneOrMesh(std::filesystem::path(WIDERAY_SOURCE_DIR) / "scenes/default.json");
    SceneAccel<8> accel(std::make_shared<const SceneGeometry>(scene));
    const std::vector<Ray> rays = primaryRays(scene, 64, 64);
    // A ray that found something visited the root (an inner node here), a leaf and a primitive; 777 is
    // what the arrays start with.
    auto notCounted = [](const TraversalCost& c) {
        return c.nodes == 0 || c.nodes == 777 || c.primitives == 0 || c.primitives == 777 || c.leaves == 0 ||
               c.leaves == 777;
    };
    auto total = [](const std::vector<TraversalCost>& costs) {
        uint64_t sum = 0;
        for (const TraversalCost& c : costs) sum += c.nodes + c.primitives;
        return sum;
    };
    for (Isa isa : supportedIsas()) {
        const KernelTable<8> table = kernelTable<8>(isa);
        std::vector<TraversalCost> singleCosts(rays.size());
        std::vector<Hit> scratch(rays.size());
        table.find("single")->intersect(accel.view(), rays.data(), scratch.data(), rays.size(), singleCosts.data());
        for (const Kernel<8>& kernel : table.rows) {
            if (!kernel.available()) continue;
            std::vector<Hit> plain(rays.size()), counted(rays.size());
            std::vector<TraversalCost> costs(rays.size(), TraversalCost{777, 777, 777});
            kernel.intersect(accel.view(), rays.data(), plain.data(), rays.size(), nullptr);
            kernel.intersect(accel.view(), rays.data(), counted.data(), rays.size(), costs.data());
            size_t uncounted = 0, changed = 0;
            for (size_t i = 0; i < rays.size(); ++i) {
                changed += std::memcmp(&plain[i], &counted[i], sizeof(Hit)) != 0;
                uncounted += counted[i].valid() && notCounted(costs[i]);
            }
            EXPECT_EQ(changed, 0u) << kernel.name << " " << isaName(isa);
            EXPECT_EQ(uncounted, 0u) << kernel.name << " " << isaName(isa) << ": hits without counted tests";
            // Occlusion counts too, without changing its answers: an occluded ray tested something.
            std::vector<uint8_t> occludedPlain(rays.size()), occludedCounted(rays.size());
            std::vector<TraversalCost> occlusionCosts(rays.size(), TraversalCost{777, 777, 777});
            kernel.occluded(accel.view(), rays.data(), occludedPlain.data(), rays.size(), nullptr);
            kernel.occluded(accel.view(), rays.data(), occludedCounted.data(), rays.size(), occlusionCosts.data());
            EXPECT_TRUE(occludedPlain == occludedCounted) << kernel.name << " " << isaName(isa);
            size_t occludedUncounted = 0;
            for (size_t i = 0; i < rays.size(); ++i)
                occludedUncounted += occludedCounted[i] && notCounted(occlusionCosts[i]);
            EXPECT_EQ(occludedUncounted, 0u) << kernel.name << " " << isaName(isa) << ": occlusion without counted tests";
            const std::string name = kernel.name;
            if (name == "scalar") {
                EXPECT_EQ(total(costs), total(singleCosts)) << "same order, same work";
            } else if (name != "single" && name != "drst") {
                // (drst visits every ray's children in its own nearest-first order and drops the rays
                // whose hits end them before a node, as a single ray does: here the same work.)
                EXPECT_NE(total(costs), total(singleCosts)) << name << " " << isaName(isa);
            }
        }
    }
}

/// Rays that start all over a mesh and mostly escape (as bounce rays do) share few nodes: packets of
/// them part singly (IncoherentPackets) instead of dragging each lane through the others' leaves, so
/// their lanes enter about as many leaves as single rays do (whole: 1.6-4.2 times as many, measured
/// while rays without a hit still entered every subtree a packet popped).
TEST(Kernels, PacketsOfFarApartRaysPartSingly) {
    FlushToZeroScope ftz;
    const SceneDescription scene = torusScene();
    SceneAccel<8> accel(std::make_shared<const SceneGeometry>(scene));
    const TriangleMesh& mesh = scene.meshes[0];
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    std::vector<Ray> rays;
    for (int i = 0; i < 4096; ++i) {
        const glm::uvec3 tri = mesh.triangles[size_t(unit(rng) * float(mesh.triangles.size() - 1))];
        const glm::vec3 a = mesh.positions[tri.x], b = mesh.positions[tri.y], c = mesh.positions[tri.z];
        float u = unit(rng), v = unit(rng);
        if (u + v > 1.0f) u = 1.0f - u, v = 1.0f - v;
        const glm::vec3 origin = a + u * (b - a) + v * (c - a);
        const glm::vec3 normal = glm::normalize(glm::cross(b - a, c - a));
        glm::vec3 d(unit(rng) - 0.5f, unit(rng) - 0.5f, unit(rng) - 0.5f);
        d = glm::normalize(d + normal);  // away from the surface, mostly
        rays.push_back({origin.x, origin.y, origin.z, d.x, d.y, d.z, 1e-4f, INFINITY});
    }
    auto leavesPerRay = [&](const Kernel<8>& kernel) {
        double leaves = 0;
        for (const TraversalCost& c : closestHitCosts(kernel, accel, rays)) leaves += c.leaves;
        return leaves / double(rays.size());
    };
    for (Isa isa : supportedIsas()) {
        const KernelTable<8> table = kernelTable<8>(isa);
        const double single = leavesPerRay(*table.find("single"));
        for (const char* name : {"packet4", "packet8", "packet16", "packet256"}) {
            const Kernel<8>* kernel = table.find(name);
            if (!kernel->available()) continue;
            EXPECT_LT(leavesPerRay(*kernel), 1.25 * single) << name << " " << isaName(isa) << ", single rays " << single;
        }
    }
}

/// A packet's lane enters a leaf only when its own ray enters the leaf's box: a ray that the
/// reference sends into no leaf (it misses every leaf box on its way) enters none in a packet either,
/// whatever order the packet takes. Rays that had found nothing yet (t = +inf) once entered every
/// subtree popped from the packet's stack, whether they entered its box or not: the same hits, with
/// up to three times the triangle tests (the coffee maker's diffuse rays, which mostly miss, in
/// 16-wide packets: 18.1 per ray, 5.8 since).
TEST(Kernels, PacketRaysEnterOnlyTheLeavesTheyReach) {
    FlushToZeroScope ftz;
    SceneDescription scene = torusScene();
    scene.camera.position = {0.3f, 2.5f, 1.5f};  // the hole and the background beside the ring
    SceneAccel<8> accel(std::make_shared<const SceneGeometry>(scene));
    const std::vector<Ray> rays = primaryRays(scene, 96, 96);
    auto leaves = [&](const Kernel<8>& kernel) {
        std::vector<uint32_t> out;
        for (const TraversalCost& c : closestHitCosts(kernel, accel, rays)) out.push_back(c.leaves);
        return out;
    };
    for (Isa isa : supportedIsas()) {
        const KernelTable<8> table = kernelTable<8>(isa);
        const std::vector<uint32_t> reference = leaves(*table.find("scalar"));
        const size_t leafless = size_t(std::count(reference.begin(), reference.end(), 0u));
        ASSERT_GT(leafless, rays.size() / 20) << "rays that reach no leaf";
        ASSERT_LT(leafless, rays.size() / 2) << "rays that do";
        for (const Kernel<8>& kernel : table.rows) {
            if (!kernel.available()) continue;
            const std::vector<uint32_t> got = leaves(kernel);
            size_t strays = 0;
            for (size_t i = 0; i < rays.size(); ++i) strays += reference[i] == 0 && got[i] != 0;
            EXPECT_EQ(strays, 0u) << kernel.name << " " << isaName(isa) << ": rays in leaves whose boxes they miss";
        }
    }
}

/// Shadow rays of one packet that end at different distances (toward lights at several distances):
/// a packet's interval may cull children beyond the farthest end of its rays, never the nearest, or
/// the longer rays would miss their occluders.
TEST(Kernels, ShadowPacketsOfUnequalLengthFindOccludersBeyondTheShortest) {
    FlushToZeroScope ftz;
    SceneDescription scene;
    scene.meshes = {makeIcosphere(4)};
    scene.instances.push_back({});
    SceneAccel<8> accel(std::make_shared<const SceneGeometry>(scene));
    const glm::vec3 d = glm::normalize(glm::vec3(0.01f, 0.02f, 1.0f));
    std::vector<Ray> rays;
    for (int i = 0; i < 1024; ++i) {
        const float x = 0.002f * float(i % 32) - 0.03f, y = 0.002f * float(i / 32) - 0.03f;
        // The sphere is 4 away: the odd rays reach it, the even ones stop short.
        rays.push_back({x, y, -5.0f, d.x, d.y, d.z, 0.0f, i % 2 ? 100.0f : 3.5f});
    }
    for (Isa isa : supportedIsas()) {
        const KernelTable<8> table = kernelTable<8>(isa);
        for (const Kernel<8>& kernel : table.rows) {
            if (!kernel.available()) continue;
            std::vector<uint8_t> occluded(rays.size(), 7);
            kernel.occluded(accel.view(), rays.data(), occluded.data(), rays.size(), nullptr);
            for (size_t i = 0; i < rays.size(); ++i)
                ASSERT_EQ(occluded[i], i % 2) << kernel.name << " " << isaName(isa) << ", ray " << i;
        }
    }
}

} // namespace
} // namespace wideray

namespace wideray {
namespace {

/// Every table has the same complete rows (the CLI lists the rows of one table as every kernel's).
TEST(Kernels, RegistryRowsAreCompleteAndTheSameInEveryTable) {
    const KernelTable<8> baseline = kernelTable<8>(Isa::Sse42);
    EXPECT_STREQ(baseline.rows[0].name, "scalar");
    for (Isa isa : supportedIsas()) {
        const KernelTable<8> table = kernelTable<8>(isa);
        for (size_t i = 0; i < table.rows.size(); ++i) {
            const Kernel<8>& k = table.rows[i];
            EXPECT_GT(std::strlen(k.name), 0u) << isaName(isa) << " row " << i;
            EXPECT_GT(std::strlen(k.description), 0u) << k.name;
            EXPECT_STREQ(k.name, baseline.rows[i].name) << isaName(isa) << " row " << i;
            EXPECT_EQ(k.available(), k.occluded != nullptr) << k.name;
            EXPECT_EQ(k.available(), int(isa) >= int(k.minimumIsa)) << k.name << " " << isaName(isa);
        }
    }
}

} // namespace
} // namespace wideray
