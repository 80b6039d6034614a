// The public C++ API (include/wideray/), linked as the shared library users get: hits against brute
// force, every way of tracing equal to single rays bit for bit, ids of meshes, instances and spheres,
// threads, and every error.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <tuple>
#include <random>
#include <limits>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "wideray/wideray.h"

namespace {

using wideray::Hit;
using wideray::Ray;

struct Mesh {
    std::vector<float> positions;
    std::vector<uint32_t> indices;
    size_t triangles() const { return indices.size() / 3; }
};

/// A bumpy closed sphere of (2 * rings * segments) triangles, shared vertices, so rays meet edges.
Mesh bumpySphere(int rings, int segments, float radius = 1.0f) {
    Mesh m;
    for (int r = 0; r <= rings; ++r)
        for (int s = 0; s < segments; ++s) {
            const double theta = M_PI * r / rings, phi = 2 * M_PI * s / segments;
            const double bump = radius * (1.0 + 0.1 * std::sin(5 * theta) * std::cos(3 * phi));
            m.positions.insert(m.positions.end(), {float(bump * std::sin(theta) * std::cos(phi)),
                                                   float(bump * std::cos(theta)),
                                                   float(bump * std::sin(theta) * std::sin(phi))});
        }
    auto at = [&](int r, int s) { return uint32_t(r * segments + (s % segments)); };
    for (int r = 0; r < rings; ++r)
        for (int s = 0; s < segments; ++s) {
            m.indices.insert(m.indices.end(), {at(r, s), at(r + 1, s), at(r + 1, s + 1)});
            m.indices.insert(m.indices.end(), {at(r, s), at(r + 1, s + 1), at(r, s + 1)});
        }
    return m;
}

/// Rays from around the box [-2, 2]^3 toward points inside [-1, 1]^3, a few with tnear and tfar set.
std::vector<Ray> randomRays(size_t n, uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> outside(-3.0f, 3.0f), inside(-1.0f, 1.0f);
    std::vector<Ray> rays(n);
    for (size_t i = 0; i < n; ++i) {
        Ray& r = rays[i];
        r.ox = outside(rng), r.oy = outside(rng), r.oz = (i % 2 ? 3.0f : -3.0f);
        r.dx = inside(rng) - r.ox, r.dy = inside(rng) - r.oy, r.dz = inside(rng) - r.oz;
        if (i % 7 == 0) r.tnear = 0.3f, r.tfar = 0.8f;
    }
    return rays;
}

/// Möller-Trumbore in double over every triangle: the closest t and its triangle, with the gap to
/// the next closest hit and how close the hit comes to the triangle's edges (to skip ambiguous rays).
struct BruteHit {
    double t = INFINITY;
    uint32_t prim = wideray::kInvalidId;
    double edgeMargin = 0, gap = INFINITY;
};

BruteHit bruteForce(const Mesh& m, const Ray& r) {
    BruteHit best;
    for (uint32_t p = 0; p < m.triangles(); ++p) {
        double v[3][3];
        for (int k = 0; k < 3; ++k)
            for (int c = 0; c < 3; ++c) v[k][c] = m.positions[3 * m.indices[3 * p + k] + c];
        const double d[3] = {r.dx, r.dy, r.dz}, o[3] = {r.ox, r.oy, r.oz};
        double e1[3], e2[3], s[3];
        for (int c = 0; c < 3; ++c) e1[c] = v[1][c] - v[0][c], e2[c] = v[2][c] - v[0][c], s[c] = o[c] - v[0][c];
        const double pv[3] = {d[1] * e2[2] - d[2] * e2[1], d[2] * e2[0] - d[0] * e2[2], d[0] * e2[1] - d[1] * e2[0]};
        const double det = e1[0] * pv[0] + e1[1] * pv[1] + e1[2] * pv[2];
        if (det == 0) continue;
        const double u = (s[0] * pv[0] + s[1] * pv[1] + s[2] * pv[2]) / det;
        const double q[3] = {s[1] * e1[2] - s[2] * e1[1], s[2] * e1[0] - s[0] * e1[2], s[0] * e1[1] - s[1] * e1[0]};
        const double vv = (d[0] * q[0] + d[1] * q[1] + d[2] * q[2]) / det;
        const double t = (e2[0] * q[0] + e2[1] * q[1] + e2[2] * q[2]) / det;
        if (u < 0 || vv < 0 || u + vv > 1 || t < r.tnear || t > r.tfar) continue;
        if (t < best.t) {
            best.gap = best.t - t;
            best = {t, p, std::min({u, vv, 1 - u - vv}), best.gap};
        } else {
            best.gap = std::min(best.gap, t - best.t);
        }
    }
    return best;
}

std::vector<Hit> singleHits(const wideray::Scene& scene, const std::vector<Ray>& rays) {
    std::vector<Hit> hits;
    for (const Ray& r : rays) hits.push_back(scene.intersect(r));
    return hits;
}

void expectSameHit(const Hit& a, const Hit& b, size_t i, const char* what) {
    EXPECT_EQ(a.primId, b.primId) << what << ", ray " << i;
    EXPECT_EQ(a.geomId, b.geomId) << what << ", ray " << i;
    // Bit for bit: every kernel of an ISA reproduces its reference exactly.
    EXPECT_EQ(std::memcmp(&a.t, &b.t, sizeof(float)), 0) << what << ", ray " << i << ": " << a.t << " vs " << b.t;
    EXPECT_EQ(a.u, b.u) << what << ", ray " << i;
    EXPECT_EQ(a.v, b.v) << what << ", ray " << i;
}

template <int K>
void expectPacketsMatch(const wideray::Scene& scene, const std::vector<Ray>& rays, const std::vector<Hit>& expected) {
    for (size_t first = 0; first + K <= rays.size(); first += K) {
        wideray::RayPacket<K> packet;
        for (int i = 0; i < K; ++i)
            if ((first / K + i) % 5 != 0) packet.set(i, rays[first + i]);  // some lanes left invalid
        const wideray::HitPacket<K> hits = scene.intersect(packet);
        const std::array<bool, K> blocked = scene.occluded(packet);
        for (int i = 0; i < K; ++i) {
            const Hit want = packet.valid[i] ? expected[first + i] : Hit{};
            expectSameHit(hits.hit(i), want, first + i, "packet");
            EXPECT_EQ(blocked[i], want.valid()) << "packet occlusion, ray " << first + i;
        }
    }
}

TEST(Library, ClosestHitsEqualBruteForce) {
    const Mesh mesh = bumpySphere(24, 40);
    wideray::Scene scene;
    const uint32_t id = scene.addTriangleMesh(mesh.positions, mesh.indices);
    scene.build();
    EXPECT_EQ(scene.primitiveCount(), mesh.triangles());
    size_t compared = 0, hits = 0;
    for (const Ray& r : randomRays(1500, 1)) {
        const BruteHit want = bruteForce(mesh, r);
        const Hit got = scene.intersect(r);
        // Rays that graze an edge or meet two surfaces at nearly the same t may go either way.
        if (want.prim != wideray::kInvalidId && (want.edgeMargin < 1e-5 || want.gap < 1e-5)) continue;
        ++compared;
        ASSERT_EQ(got.primId, want.prim) << "ray from " << r.ox << "," << r.oy << "," << r.oz;
        if (!got.valid()) continue;
        ++hits;
        EXPECT_EQ(got.geomId, id);
        EXPECT_NEAR(got.t, want.t, 1e-5 * (1 + want.t));
    }
    EXPECT_GT(compared, 1400u);
    EXPECT_GT(hits, 300u);
}

TEST(Library, PacketsAndStreamsEqualSingleRays) {
    const Mesh mesh = bumpySphere(30, 50);
    const std::vector<Ray> rays = randomRays(5000, 2);
    for (const char* quality : {"fast", "high"}) {
        wideray::SceneOptions options;
        options.quality = std::string(quality) == "high" ? wideray::BuildQuality::High : wideray::BuildQuality::Fast;
        wideray::Scene scene(options);
        scene.addTriangleMesh(mesh.positions, mesh.indices);
        scene.build();
        const std::vector<Hit> expected = singleHits(scene, rays);

        // The reference kernel (scalar, same ISA) agrees with the default single-ray kernel.
        options.kernel = "scalar";
        wideray::Scene reference(options);
        reference.addTriangleMesh(mesh.positions, mesh.indices);
        reference.build();
        for (size_t i = 0; i < rays.size(); ++i) expectSameHit(reference.intersect(rays[i]), expected[i], i, quality);

        expectPacketsMatch<4>(scene, rays, expected);
        expectPacketsMatch<8>(scene, rays, expected);
        expectPacketsMatch<16>(scene, rays, expected);
        for (auto coherence : {wideray::Coherence::Coherent, wideray::Coherence::Incoherent})
            for (auto threading : {wideray::Threading::Caller, wideray::Threading::Parallel}) {
                std::vector<Hit> hits(rays.size());
                std::vector<uint8_t> blocked(rays.size(), 7);
                scene.intersect(rays, hits, coherence, threading);
                scene.occluded(rays, blocked, coherence, threading);
                for (size_t i = 0; i < rays.size(); ++i) {
                    expectSameHit(hits[i], expected[i], i, "stream");
                    EXPECT_EQ(blocked[i], expected[i].valid() ? 1 : 0) << "stream occlusion, ray " << i;
                    EXPECT_EQ(scene.occluded(rays[i]), expected[i].valid()) << "single occlusion, ray " << i;
                }
            }
    }
}

TEST(Library, InstancesNameTheirMeshTrianglesLikeACopy) {
    const Mesh mesh = bumpySphere(10, 16, 0.4f);
    // A mirrored, turned and moved placement, written out as a mesh of its own for comparison.
    wideray::Transform mirror;
    const float m[3][4] = {{0, -1, 0, 0.5f}, {-1, 0, 0, 0.2f}, {0, 0, 1.5f, -0.1f}};
    std::copy(&m[0][0], &m[0][0] + 12, &mirror.m[0][0]);
    Mesh moved = mesh;
    for (size_t v = 0; v < mesh.positions.size(); v += 3)
        for (int r = 0; r < 3; ++r)
            moved.positions[v + r] = m[r][0] * mesh.positions[v] + m[r][1] * mesh.positions[v + 1] +
                                     m[r][2] * mesh.positions[v + 2] + m[r][3];
    // Few copies are flattened into the world; many are two-level, with a BVH of the mesh's own.
    for (int copies : {1, 300}) {
        wideray::Scene instanced, copied;
        const uint32_t original = instanced.addTriangleMesh(mesh.positions, mesh.indices);
        const uint32_t copiedOriginal = copied.addTriangleMesh(mesh.positions, mesh.indices);
        uint32_t instance = 0;
        for (int c = 0; c < copies; ++c) {
            wideray::Transform far;  // the other copies far away from the rays
            far.m[0][3] = 100.0f + 3.0f * float(c);
            instance = instanced.addInstance(original, c + 1 == copies ? mirror : far);
        }
        const uint32_t copiedMoved = copied.addTriangleMesh(moved.positions, moved.indices);
        instanced.build();
        copied.build();
        size_t onInstance = 0;
        for (const Ray& r : randomRays(2000, 3)) {
            const Hit a = instanced.intersect(r), b = copied.intersect(r);
            ASSERT_EQ(a.valid(), b.valid());
            if (!a.valid()) continue;
            EXPECT_EQ(a.primId, b.primId);
            EXPECT_EQ(a.geomId == instance, b.geomId == copiedMoved);
            EXPECT_EQ(a.geomId == original, b.geomId == copiedOriginal);
            EXPECT_NEAR(a.t, b.t, 1e-4f);
            EXPECT_NEAR(a.u, b.u, 1e-3f);
            EXPECT_NEAR(a.v, b.v, 1e-3f);
            onInstance += a.geomId == instance;
        }
        EXPECT_GT(onInstance, 100u) << copies << " copies";
    }
}

TEST(Library, SpheresAndMeshesHaveTheirOwnIds) {
    wideray::Scene scene;
    const Mesh mesh = bumpySphere(6, 8, 0.5f);
    const uint32_t meshId = scene.addTriangleMesh(mesh.positions, mesh.indices);
    const std::vector<float> centers = {3, 0, 0, 6, 0, 0}, radii = {1, 0.5f};
    const uint32_t first = scene.addSpheres(centers, radii);
    const uint32_t second = scene.addSpheres(std::vector<float>{9, 0, 0}, std::vector<float>{2});
    EXPECT_EQ(meshId, 0u);
    EXPECT_EQ(first, 1u);
    EXPECT_EQ(second, 2u);
    scene.build();
    const Hit a = scene.intersect({6, 0, -10, 0, 0, 1});
    EXPECT_EQ(a.geomId, first);
    EXPECT_EQ(a.primId, 1u);
    EXPECT_NEAR(a.t, 9.5f, 1e-5f);
    const Hit b = scene.intersect({9, 0, -10, 0, 0, 1});
    EXPECT_EQ(b.geomId, second);
    EXPECT_EQ(b.primId, 0u);
    EXPECT_NEAR(b.t, 8.0f, 1e-5f);
    EXPECT_EQ(scene.intersect({0, 0, -10, 0, 0, 1}).geomId, meshId);
    const std::array<float, 6> box = scene.bounds();
    EXPECT_FLOAT_EQ(box[3], 11.0f);
    EXPECT_LT(box[0], -0.45f);  // the mesh, of radius 0.5 +- 10%
    EXPECT_GT(box[0], -0.56f);
}

TEST(Library, SharedArraysAreReadByBuild) {
    const Mesh mesh = bumpySphere(12, 20);
    std::vector<float> positions(mesh.positions.size(), 0.0f);
    wideray::Scene shared, copied;
    shared.addTriangleMesh(positions, mesh.indices, wideray::Sharing::Shared);
    copied.addTriangleMesh(mesh.positions, mesh.indices);
    positions = mesh.positions;  // same size: the span stays valid; build() reads what is there now
    shared.build();
    copied.build();
    const std::vector<Ray> rays = randomRays(500, 4);
    const std::vector<Hit> expected = singleHits(copied, rays);
    for (size_t i = 0; i < rays.size(); ++i) expectSameHit(shared.intersect(rays[i]), expected[i], i, "shared");
    // Checked again at every build, the error names the build and the mesh.
    positions[7] = std::numeric_limits<float>::quiet_NaN();
    try {
        shared.build();
        ADD_FAILURE() << "a shared mesh with NaN was built";
    } catch (const wideray::Error& e) {
        EXPECT_NE(std::string(e.what()).find("build: shared mesh (geomId 0): positions[7] (vertex 2) is nan"), std::string::npos)
            << e.what();
    }
}

TEST(Library, TracesFromTheCallersThreads) {
    const Mesh mesh = bumpySphere(30, 50);
    wideray::Scene scene;
    scene.addTriangleMesh(mesh.positions, mesh.indices);
    scene.build();
    const std::vector<Ray> rays = randomRays(4000, 5);
    const std::vector<Hit> expected = singleHits(scene, rays);
    std::vector<std::thread> threads;
    std::vector<int> mismatches(4, 0);
    for (int t = 0; t < 4; ++t)
        threads.emplace_back([&, t] {
            std::vector<Hit> hits(rays.size());
            scene.intersect(rays, hits, t % 2 ? wideray::Coherence::Coherent : wideray::Coherence::Incoherent);
            for (size_t i = 0; i < rays.size(); ++i) {
                const Hit single = scene.intersect(rays[i]);
                mismatches[size_t(t)] += hits[i].primId != expected[i].primId || single.t != expected[i].t;
            }
        });
    for (std::thread& t : threads) t.join();
    for (int m : mismatches) EXPECT_EQ(m, 0);
}

template <typename F>
void expectError(F&& f, const std::string& part) {
    try {
        f();
        ADD_FAILURE() << "no error; expected one mentioning '" << part << "'";
    } catch (const wideray::Error& e) {
        EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what();
    }
}

TEST(Library, ErrorsSayWhatIsWrong) {
    const std::vector<float> triangle = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    wideray::Scene scene;
    expectError([&] { scene.addTriangleMesh(triangle, std::vector<uint32_t>{0, 1, 3}); },
                "indices[2] (triangle 0) is 3, but the mesh has 3 vertices");
    expectError([&] { scene.addTriangleMesh(std::vector<float>{0, 0}, std::vector<uint32_t>{}); }, "not 3 per vertex");
    expectError([&] { scene.addTriangleMesh(std::vector<float>{0, 0, NAN}, std::vector<uint32_t>{}); },
                "positions[2] (vertex 0) is nan");
    expectError([&] { scene.addInstance(7, {}); }, "geomId 7 is not a mesh");
    expectError([&] { scene.addSpheres(std::vector<float>{0, 0, 0}, std::vector<float>{-1}); }, "radii[0] is -1");
    expectError([&] { scene.intersect(Ray{}); }, "build() the scene before tracing");
    const uint32_t mesh = scene.addTriangleMesh(triangle, std::vector<uint32_t>{0, 1, 2});
    wideray::Transform flat;
    flat.m[2][2] = 0;
    expectError([&] { scene.addInstance(mesh, flat); }, "singular");
    scene.build();
    std::vector<Hit> hits(1);
    expectError([&] { scene.intersect(std::vector<Ray>(2), hits); }, "2 rays but room for 1 hits");
    scene.addSpheres(std::vector<float>{0, 0, 5}, std::vector<float>{1});
    expectError([&] { scene.intersect(Ray{}); }, "and again after adding to it");

    wideray::SceneOptions wide;
    wide.bvhWidth = 5;
    expectError([&] { wideray::Scene{wide}; }, "bvhWidth: must be 4, 8 or 16");
    for (auto [kernel, isa, message] : {std::tuple{"fastest", "", "SceneOptions::kernel: no kernel is named 'fastest'"},
                                        {"", "avx9", "SceneOptions::isa: 'avx9' is not one of"}}) {
        wideray::SceneOptions options;
        options.kernel = kernel;
        options.isa = isa;
        wideray::Scene s(options);
        s.addTriangleMesh(triangle, std::vector<uint32_t>{0, 1, 2});
        expectError([&] { s.build(); }, message);
    }
}

TEST(Library, RendersSceneFiles) {
    const std::string file = std::string(WIDERAY_SOURCE_DIR) + "/scenes/default.json";
    wideray::RenderRequest small;
    small.width = 64, small.height = 48;
    const wideray::RenderedImage image = wideray::renderSceneFile(file, small);
    ASSERT_EQ(image.width, 64);
    ASSERT_EQ(image.height, 48);
    ASSERT_EQ(image.rgb.size(), size_t(64 * 48 * 3));
    double sum = 0;
    for (float c : image.rgb) {
        ASSERT_TRUE(std::isfinite(c));
        sum += c;
    }
    EXPECT_GT(sum, 0.0);
    expectError([] { wideray::renderSceneFile("no/such/scene.json"); }, "no/such/scene.json");
    wideray::RenderRequest photon;
    photon.integrator = "photon";
    expectError([&] { wideray::renderSceneFile(file, photon); }, "integrator 'photon'");
    EXPECT_STREQ(wideray::version(), WIDERAY_VERSION_STRING);
}

} // namespace
