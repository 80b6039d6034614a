// The course's structures (bvh2, skip, kdtree, grid, hgrid, rgrid): every one returns exactly the
// hits of the scalar reference of the same ISA over the wide BVH (same primitive, t, u, v, bit for
// bit) and the same occlusion, and the baseline's hits equal brute force; the watertight cases and
// the structures' own corner cases (cells, planes, empty leaves) too.
#include <gtest/gtest.h>

#include <cstring>

#include <tbb/global_control.h>
#include <tbb/parallel_for.h>

#include "accel/grid_build.h"
#include "accel/kdtree_build.h"
#include "accel/scene_accel.h"
#include "backends/accel_registry.h"
#include "backends/course_structure.h"
#include "core/error.h"
#include "core/fp_mode.h"
#include "geometry/triangle_geometry.h"
#include "io/mesh_framing.h"
#include "io/mesh_generators.h"
#include "kernels/kernel_registry.h"
#include "render/bench_rays.h"
#include "render/renderer.h"
#include "backends/wideray_structure.h"
#include "ray_sets.h"
#include "test_data.h"

namespace wideray {
namespace {

/// Every structure of the registry that is not a wide BVH.
std::vector<std::string> courseAccels() {
    std::vector<std::string> names;
    for (const Accel& a : accels())
        if (!a.wideBvh) names.push_back(a.name);
    return names;
}

std::shared_ptr<const CourseStructure> buildCourse(const std::string& name, std::shared_ptr<const SceneGeometry> g) {
    StructureOptions options;
    options.accel = name;
    return std::dynamic_pointer_cast<const CourseStructure>(findBackend("wideray").build(std::move(g), options));
}

bool sameHit(const Hit& a, const Hit& b) {
    return a.primId == b.primId && a.geomId == b.geomId && std::memcmp(&a.t, &b.t, 4) == 0 &&
           std::memcmp(&a.u, &b.u, 4) == 0 && std::memcmp(&a.v, &b.v, 4) == 0;
}

/// Each course structure against the reference of every ISA, closest hit and any hit.
void expectMatchesReference(std::shared_ptr<const SceneGeometry> geometry, const std::vector<Ray>& rays,
                            const std::string& what) {
    SceneAccel<8> reference(geometry, SceneAccel<8>::defaultConfig());
    for (const std::string& name : courseAccels()) {
        std::shared_ptr<const CourseStructure> s = buildCourse(name, geometry);
        for (Isa isa : supportedIsas()) {
            std::vector<Hit> expected(rays.size()), hits(rays.size());
            std::vector<uint8_t> expectedOccluded(rays.size()), occluded(rays.size(), 7);
            referenceKernel<8>(isa).intersect(reference.view(), rays.data(), expected.data(), rays.size(), nullptr);
            referenceKernel<8>(isa).occluded(reference.view(), rays.data(), expectedOccluded.data(), rays.size(), nullptr);
            s->trace(isa, rays.data(), rays.size(), hits.data(), nullptr, nullptr);
            s->trace(isa, rays.data(), rays.size(), nullptr, occluded.data(), nullptr);
            size_t hitMismatches = 0, occlusionMismatches = 0;
            for (size_t i = 0; i < rays.size(); ++i) {
                if (!sameHit(hits[i], expected[i]) && ++hitMismatches <= 3)
                    ADD_FAILURE() << what << " " << name << " " << isaName(isa) << " ray " << i << ": prim "
                                  << hits[i].primId << " t " << hits[i].t << " vs reference prim " << expected[i].primId
                                  << " t " << expected[i].t;
                if (occluded[i] != expectedOccluded[i] && ++occlusionMismatches <= 3)
                    ADD_FAILURE() << what << " " << name << " " << isaName(isa) << " ray " << i << ": occluded "
                                  << int(occluded[i]) << " vs reference " << int(expectedOccluded[i]);
            }
            EXPECT_EQ(hitMismatches, 0u) << what << " " << name << " " << isaName(isa) << " of " << rays.size();
            EXPECT_EQ(occlusionMismatches, 0u) << what << " " << name << " " << isaName(isa) << " of " << rays.size();
        }
    }
}

/// The baseline kernels against brute force (which shares the baseline's arithmetic), on a sample.
void expectMatchesBruteForce(const TriangleMesh& mesh, const std::vector<Ray>& rays, const std::string& what) {
    auto geometry = std::make_shared<const SceneGeometry>(mesh);
    std::vector<Hit> expected(rays.size());
    for (size_t i = 0; i < rays.size(); ++i) expected[i] = testing::bruteForceHit(mesh, rays[i]);
    for (const std::string& name : courseAccels()) {
        std::vector<Hit> hits(rays.size());
        buildCourse(name, geometry)->trace(Isa::Sse42, rays.data(), rays.size(), hits.data(), nullptr, nullptr);
        size_t mismatches = 0;
        for (size_t i = 0; i < rays.size(); ++i) mismatches += !sameHit(hits[i], expected[i]);
        EXPECT_EQ(mismatches, 0u) << what << " " << name << " against brute force, of " << rays.size();
    }
}

/// Camera, shadow and diffuse rays of a scene, and random rays through its meshes.
void checkScene(const SceneDescription& scene, int size, size_t bruteForceRays) {
    FlushToZeroScope ftz;
    auto geometry = std::make_shared<const SceneGeometry>(scene);
    auto reference = buildWideBvh(geometry, {})->tracer({"scalar"});
    BenchRays rays = makeBenchRays(scene, *reference, size, size);
    expectMatchesReference(geometry, rays.primary, "primary");
    expectMatchesReference(geometry, rays.shadow, "shadow");
    expectMatchesReference(geometry, rays.diffuse, "diffuse");
    const TriangleMesh world = flattenTriangles(scene);
    if (world.triangles.empty()) return;
    std::vector<Ray> random = testing::randomRays(world, size_t(size) * size / 4, 5);
    expectMatchesReference(geometry, random, "random");
    if (scene.spheres.empty()) {
        random.resize(std::min(random.size(), bruteForceRays));
        expectMatchesBruteForce(world, random, "random");
    }
}

TEST(Accelerators, RegistryNamesEveryStructure) {
    const std::vector<std::string> expected = {"bvh8",   "bvh4", "bvh16", "bvh2", "skip",
                                               "kdtree", "grid", "hgrid", "rgrid"};
    std::vector<std::string> names;
    for (const Accel& a : accels()) names.push_back(a.name);
    EXPECT_EQ(names, expected);
    EXPECT_THROW(findAccel("octree"), InputError);
}

TEST(Accelerators, MatchReferenceOnDefaultScene) {
    // Triangles and spheres (user primitives) together.
    checkScene(loadSceneOrMesh(std::filesystem::path(WIDERAY_SOURCE_DIR) / "scenes/default.json"), 96, 0);
}

TEST(Accelerators, MatchReferenceAndBruteForceOnGeneratedMeshes) {
    for (TriangleMesh mesh : {makeTorus(1.0f, 0.3f, 64, 32), makeIcosphere(3), makeCube()}) {
        SceneDescription scene = sceneFromMesh(mesh, 64, 64);
        checkScene(scene, 64, 512);
    }
}

class SharedMeshAccelerators : public ::testing::TestWithParam<const char*> {};

TEST_P(SharedMeshAccelerators, MatchReferenceAndBruteForce) {
    auto dir = sharedScenesDir();
    if (!dir) GTEST_SKIP() << "needs ../shared/scenes (or WIDERAY_SCENES)";
#ifdef WIDERAY_SANITIZE
    // Six builds of Sponza take minutes under the sanitizers; the smaller meshes cover the same code.
    if (std::string_view(GetParam()).find("sponza") != std::string_view::npos) GTEST_SKIP() << "large mesh, sanitizer build";
    const int size = 24;
#else
    const int size = 64;
#endif
    SceneDescription scene = sceneFromMesh(*dir / GetParam(), size, size);
    checkScene(scene, size, 64);
}

INSTANTIATE_TEST_SUITE_P(RealMeshes, SharedMeshAccelerators,
                         ::testing::Values("cornell-box/CornellBox-Original.obj", "teapot/teapot.obj",
                                           "stanford-bunny/bun_zipper.ply", "crytek-sponza/sponza.obj"));

/// Rays of every ISA's reference against every structure, one at a time.
void expectSameOnRays(const TriangleMesh& mesh, const std::vector<Ray>& rays, const char* what) {
    expectMatchesReference(std::make_shared<const SceneGeometry>(mesh), rays, what);
}

TEST(Accelerators, WatertightFromInsideClosedMeshes) {
    // Rays from the center at every vertex and along every edge never slip through.
    for (const TriangleMesh& mesh : {makeIcosphere(2), makeCube()}) {
        auto geometry = std::make_shared<const SceneGeometry>(mesh);
        std::vector<Ray> rays;
        for (const glm::vec3& v : mesh.positions) rays.push_back({0.01f, -0.02f, 0.03f, v.x, v.y, v.z, 0.0f, 1e30f});
        for (const glm::uvec3& t : mesh.triangles)
            for (int e = 0; e < 3; ++e) {
                const glm::vec3 a = mesh.positions[t[e]], b = mesh.positions[t[(e + 1) % 3]], p = a + 0.5f * (b - a);
                rays.push_back({0.01f, -0.02f, 0.03f, p.x, p.y, p.z, 0.0f, 1e30f});
            }
        for (const std::string& name : courseAccels())
            for (Isa isa : supportedIsas()) {
                std::vector<Hit> hits(rays.size());
                buildCourse(name, geometry)->trace(isa, rays.data(), rays.size(), hits.data(), nullptr, nullptr);
                size_t misses = 0;
                for (const Hit& h : hits) misses += !h.valid();
                EXPECT_EQ(misses, 0u) << name << " " << isaName(isa) << " of " << rays.size();
            }
    }
}

TEST(Accelerators, AxisParallelRaysAlongCellBoundariesAndPlanes) {
    // A grid of unit quads in the z = 0 plane: rays along x and y lie exactly in cell boundaries and
    // split planes, rays along z start inside cells and hit edges and corners.
    TriangleMesh mesh;
    const int n = 8;
    for (int y = 0; y <= n; ++y)
        for (int x = 0; x <= n; ++x) mesh.positions.push_back({float(x), float(y), float((x * 7 + y * 3) % 5) * 0.25f});
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) {
            const uint32_t i = uint32_t(y * (n + 1) + x);
            mesh.triangles.push_back({i, i + 1, i + uint32_t(n) + 2});
            mesh.triangles.push_back({i, i + uint32_t(n) + 2, i + uint32_t(n) + 1});
        }
    std::vector<Ray> rays;
    for (int i = 0; i <= 4 * n; ++i)
        for (int j = 0; j <= 4 * n; ++j) {
            const float a = float(i) * 0.25f, b = float(j) * 0.25f;
            rays.push_back({a, b, 5.0f, 0.0f, 0.0f, -1.0f, 0.0f, 1e30f});   // down through cells, edges, corners
            rays.push_back({a, b, -5.0f, 0.0f, 0.0f, 1.0f, 0.0f, 1e30f});   // up, from below
            rays.push_back({-1.0f, a, b * 0.125f, 1.0f, 0.0f, 0.0f, 0.0f, 1e30f});  // along x, in planes y = a
            rays.push_back({a, 9.0f, b * 0.125f, 0.0f, -1.0f, 0.0f, 0.0f, 1e30f});  // along -y
            rays.push_back({a, b, 0.5f, 0.0f, 0.0f, -1.0f, 0.0f, 1e30f});   // starting inside a cell
        }
    expectSameOnRays(mesh, rays, "axis-parallel");
    std::vector<Hit> hits(rays.size());
    buildCourse("grid", std::make_shared<const SceneGeometry>(mesh))
        ->trace(bestIsa(), rays.data(), rays.size(), hits.data(), nullptr, nullptr);
    size_t downHits = 0;
    for (size_t i = 0; i < rays.size(); i += 5) downHits += hits[i].valid();
    EXPECT_EQ(downHits, size_t(4 * n + 1) * size_t(4 * n + 1));  // every ray down hits the surface
}

TEST(Accelerators, RaysAlongTheGridsCellBoundaries) {
    // Rays lying exactly in the planes between cells, as the walk computes them, and through the
    // lines where four cells meet.
    TriangleMesh mesh = makeTorus(1.0f, 0.4f, 48, 24);
    auto geometry = std::make_shared<const SceneGeometry>(mesh);
    const Grid grid = buildGrid(PrimitiveTable(*geometry), uniformGridConfig());
    const GridLevel& g = grid.grids[0];
    std::vector<Ray> rays;
    for (int i = 1; i < g.res[0]; ++i)
        for (int j = 1; j < g.res[2]; ++j) {
            const float x = g.lower[0] + float(i) * g.cellSize[0], z = g.lower[2] + float(j) * g.cellSize[2];
            rays.push_back({x, g.lower[1] - 1.0f, z, 0.0f, 1.0f, 0.0f, 0.0f, 1e30f});  // along y, on two boundaries
            rays.push_back({x, g.upper[1] + 1.0f, z + 0.3f * g.cellSize[2], 0.0f, -1.0f, 0.0f, 0.0f, 1e30f});  // in x planes
            rays.push_back({x, g.lower[1] + 0.5f * (g.upper[1] - g.lower[1]), z, 0.0f, 0.0f, 1.0f, 0.0f, 1e30f});  // from inside
        }
    ASSERT_GT(rays.size(), 100u);
    expectSameOnRays(mesh, rays, "cell boundaries");
}

TEST(Accelerators, OneCellGridAndOneTriangle) {
    TriangleMesh mesh = makeQuad();
    mesh.triangles.resize(1);
    auto geometry = std::make_shared<const SceneGeometry>(mesh);
    const PrimitiveTable table(*geometry);
    GridConfig config;
    config.density = 1e-6f;
    const Grid grid = buildGrid(table, config);
    ASSERT_EQ(grid.cells.size(), 1u);
    EXPECT_EQ(grid.cells[0].count, 1u);
    std::vector<Ray> rays = testing::randomRays(mesh, 2000, 3);
    expectSameOnRays(mesh, rays, "one triangle");
}

TEST(Accelerators, FlatSceneFarFromTheOrigin) {
    // One triangle in the plane z = 1e5: the grid's flat axis must still get a thickness there.
    TriangleMesh mesh;
    mesh.positions = {{0, 0, 1e5f}, {1, 0, 1e5f}, {0, 1, 1e5f}};
    mesh.triangles = {{0, 1, 2}};
    auto geometry = std::make_shared<const SceneGeometry>(mesh);
    for (const GridConfig& config : {uniformGridConfig(), recursiveGridConfig()}) {
        const Grid grid = buildGrid(PrimitiveTable(*geometry), config);
        ASSERT_FALSE(grid.grids.empty());
        for (int a = 0; a < 3; ++a) EXPECT_GE(grid.grids[0].res[a], 1);
        EXPECT_GT(grid.grids[0].upper[2], grid.grids[0].lower[2]);
    }
    std::vector<Ray> rays;
    for (int i = 0; i < 50; ++i)
        rays.push_back({0.02f * float(i), 0.3f, 1e5f - 10.0f, 0.0f, 0.0f, 1.0f, 0.0f, 1e30f});
    expectSameOnRays(mesh, rays, "flat far triangle");
}

TEST(Accelerators, KdTreeCutsOffEmptySpaceIntoEmptyLeaves) {
    // Two small clusters far apart: the SAH cuts the empty space between them off into empty leaves.
    TriangleMesh mesh = makeIcosphere(2);
    const size_t vertices = mesh.positions.size(), triangles = mesh.triangles.size();
    for (size_t i = 0; i < vertices; ++i) mesh.positions.push_back(mesh.positions[i] + glm::vec3(20.0f, 0.0f, 0.0f));
    for (size_t i = 0; i < triangles; ++i) mesh.triangles.push_back(mesh.triangles[i] + glm::uvec3(uint32_t(vertices)));
    auto geometry = std::make_shared<const SceneGeometry>(mesh);
    const KdTree tree = buildKdTree(PrimitiveTable(*geometry));
    EXPECT_GT(tree.emptyLeaves, 0u);
    EXPECT_LE(tree.depth, kMaxKdTreeDepth);
    std::vector<Ray> rays = testing::randomRays(mesh, 4000, 9);
    for (int i = 0; i < 200; ++i)  // through the empty middle
        rays.push_back({10.0f, float(i % 20) * 0.1f - 1.0f, -5.0f, 0.01f * float(i - 100), 0.0f, 1.0f, 0.0f, 1e30f});
    expectSameOnRays(mesh, rays, "two clusters");
}

TEST(Accelerators, EmptySceneMissesEverything) {
    SceneDescription scene;
    auto geometry = std::make_shared<const SceneGeometry>(scene);
    const Ray ray{0, 0, 0, 0, 0, 1, 0, 1e30f};
    for (const std::string& name : courseAccels()) {
        Hit hit;
        uint8_t occluded = 7;
        auto s = buildCourse(name, geometry);
        s->trace(bestIsa(), &ray, 1, &hit, nullptr, nullptr);
        s->trace(bestIsa(), &ray, 1, nullptr, &occluded, nullptr);
        EXPECT_FALSE(hit.valid()) << name;
        EXPECT_EQ(occluded, 0) << name;
    }
}

TEST(Accelerators, MailboxGivesTheSameHitsOnOneAndTwoThreads) {
    TriangleMesh mesh = makeTorus(1.0f, 0.3f, 96, 48);
    std::vector<Ray> rays = testing::randomRays(mesh, 20000, 21);
    auto geometry = std::make_shared<const SceneGeometry>(mesh);
    for (const char* name : {"kdtree", "grid", "hgrid", "rgrid"}) {
        auto s = buildCourse(name, geometry);
        auto tracer = s->tracer({});
        std::vector<Hit> one(rays.size()), two(rays.size());
        std::vector<TraversalCost> costs(rays.size());
        {
            tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
            s->trace(bestIsa(), rays.data(), rays.size(), one.data(), nullptr, costs.data());
        }
        {
            tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 2);
            tbb::parallel_for(tbb::blocked_range<size_t>(0, rays.size(), 64), [&](const tbb::blocked_range<size_t>& r) {
                tracer->intersect({rays.data() + r.begin(), r.size()}, {two.data() + r.begin(), r.size()},
                                  Coherence::Incoherent);
            });
        }
        size_t mismatches = 0, mailboxHits = 0;
        for (size_t i = 0; i < rays.size(); ++i) mismatches += !sameHit(one[i], two[i]);
        for (const TraversalCost& c : costs) mailboxHits += c.mailboxHits;
        EXPECT_EQ(mismatches, 0u) << name;
        EXPECT_GT(mailboxHits, 0u) << name << ": the mailbox saved no test";
    }
}

TEST(Accelerators, HierarchicalGridsRefineCrowdedCells) {
    // A dense sphere in a large sparse box (a teapot in a stadium): the uniform grid leaves the sphere
    // in few crowded cells; hgrid and rgrid refine them.
    TriangleMesh mesh = makeIcosphere(4);
    const uint32_t base = uint32_t(mesh.positions.size());
    for (const glm::vec3& p : {glm::vec3(-100, -100, -1.5f), glm::vec3(100, -100, -1.5f), glm::vec3(100, 100, -1.5f),
                               glm::vec3(-100, 100, -1.5f)})
        mesh.positions.push_back(p);
    mesh.triangles.push_back({base, base + 1, base + 2});
    mesh.triangles.push_back({base, base + 2, base + 3});
    auto geometry = std::make_shared<const SceneGeometry>(mesh);
    const PrimitiveTable table(*geometry);
    EXPECT_EQ(buildGrid(table, uniformGridConfig()).levels, 1);
    EXPECT_GE(buildGrid(table, hierarchicalGridConfig()).levels, 2);
    EXPECT_GE(buildGrid(table, recursiveGridConfig()).levels, 3);
    std::vector<Ray> rays = testing::randomRays(mesh, 4000, 17);
    for (int i = 0; i < 1000; ++i)  // from far away at the sphere
        rays.push_back({float(i % 40) - 20.0f, -90.0f, 0.3f, (20.0f - float(i % 40)) * 0.01f, 1.0f, float(i / 40) * 0.001f - 0.0125f, 0.0f, 1e30f});
    expectSameOnRays(mesh, rays, "sphere in a stadium");
}

TEST(Accelerators, CourseStructuresHaveOneKernel) {
    auto geometry = std::make_shared<const SceneGeometry>(makeCube());
    for (const std::string& name : courseAccels()) {
        auto s = buildCourse(name, geometry);
        EXPECT_NO_THROW(s->tracer({"single"})) << name;
        EXPECT_THROW(s->tracer({"packet4"}), InputError) << name;
        EXPECT_GT(s->bytes(), 0u) << name;
        EXPECT_NE(s->summary().find(s->name()), std::string::npos) << name;
    }
    StructureOptions high;
    high.accel = "kdtree";
    high.quality = "high";
    EXPECT_THROW(findBackend("wideray").build(geometry, high), InputError);
}

TEST(Accelerators, RenderTheSameImageAndDrawTheirCost) {
    // Same hits, so the same image: the default scene (mirror, glass, spheres, shadows) through every
    // structure equals the render through the scalar reference of the same ISA; the cost AOV draws
    // each structure's own work.
    FlushToZeroScope ftz;
    SceneDescription scene = loadSceneOrMesh(std::filesystem::path(WIDERAY_SOURCE_DIR) / "scenes/default.json");
    auto geometry = std::make_shared<const SceneGeometry>(scene);
    RenderOptions options;
    options.width = options.height = 48;
    RenderStats stats;
    const Image expected = render(scene, *buildWideBvh(geometry, {})->tracer({"scalar"}), options, stats);
    for (const std::string& name : courseAccels()) {
        auto s = buildCourse(name, geometry);
        options.aov = Aov::Color;
        EXPECT_TRUE(render(scene, *s->tracer({}), options, stats).pixels == expected.pixels) << name;
        options.aov = Aov::Cost;
        render(scene, *s->tracer({}), options, stats);
        EXPECT_GT(stats.maxCost, 0u) << name;
    }
}

} // namespace
} // namespace wideray
