// Fractal terrain: the ridged multifractal heights, the generated mesh, and the height-field
// primitive traced directly, which agrees with the mesh's triangles through the BVH.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "backends/backend_registry.h"
#include "core/error.h"
#include "io/scene_parser.h"
#include "io/terrain.h"
#include "scene_errors.h"

namespace wideray {
namespace {

TEST(Terrain, RidgedMultifractalIsDeterministicAndScaled) {
    TerrainParameters p;
    p.resolution = 64;
    p.height = 0.4f;
    const std::vector<float> a = ridgedMultifractalHeights(p), b = ridgedMultifractalHeights(p);
    ASSERT_EQ(a.size(), size_t(65 * 65));
    EXPECT_EQ(a, b);
    EXPECT_EQ(*std::min_element(a.begin(), a.end()), 0.0f);
    EXPECT_FLOAT_EQ(*std::max_element(a.begin(), a.end()), 0.4f);
    p.seed = 3;
    EXPECT_NE(ridgedMultifractalHeights(p), a);
    const TriangleMesh mesh = heightFieldMesh(a, 64);
    EXPECT_EQ(mesh.triangles.size(), size_t(2 * 64 * 64));
}

constexpr const char* kTerrainObject = R"("resolution": 48, "octaves": 5, "height": 0.35, "seed": 2,
     "transform": {"scale": [3, 2, 3], "rotate": {"axis": [0, 1, 0], "degrees": 20}, "translate": [0.5, -1, 0]})";

SceneDescription terrainScene(const char* type) {
    const std::string object = std::string(type) == "heightfield" ? R"({"type": "heightfield", )"
                                                                    : R"({"type": "generated", "shape": "terrain", )";
    return parseScene(R"({"lights": [{"type": "point", "position": [0, 5, 0]}], "objects": [)" + object + kTerrainObject + "}]}",
                      "terrain.json");
}

TEST(Terrain, HeightFieldAgreesWithTheMesh) {
    const SceneDescription field = terrainScene("heightfield"), mesh = terrainScene("generated");
    ASSERT_EQ(field.heightFields.size(), 1u);
    std::mt19937 rng(4);
    std::uniform_real_distribution<float> dist(0.0f, 1.0f);
    auto unit = [&] { return dist(rng); };
    std::vector<Ray> rays;
    for (int i = 0; i < 20000; ++i) {
        const glm::vec3 o(8 * unit() - 4, 1.5f * unit() - 0.5f, 8 * unit() - 4);
        // Steep and grazing: the target's height spread is small, so many rays run along the ridges.
        const glm::vec3 target(6 * unit() - 3, -1.0f + 0.7f * unit(), 6 * unit() - 3);
        const glm::vec3 d = glm::normalize(target - o);
        rays.push_back({o.x, o.y, o.z, d.x, d.y, d.z, 0.0f, std::numeric_limits<float>::infinity()});
    }
    auto trace = [&](const SceneDescription& scene, const std::string& accel) {
        StructureOptions options;
        options.accel = accel;
        std::vector<Hit> hits(rays.size());
        findBackend("wideray").build(std::make_shared<const SceneGeometry>(scene), options)->tracer({})->intersect(
            rays, hits, Coherence::Incoherent);
        return hits;
    };
    const std::vector<Hit> expected = trace(mesh, "bvh8");
    for (const char* accel : {"bvh8", "kdtree"}) {
        const std::vector<Hit> hits = trace(field, accel);
        size_t both = 0, disagree = 0;
        for (size_t i = 0; i < rays.size(); ++i) {
            if (hits[i].valid() != expected[i].valid()) {
                ++disagree;
                continue;
            }
            if (!hits[i].valid()) continue;
            ++both;
            EXPECT_NEAR(hits[i].t, expected[i].t, 1e-4f * expected[i].t) << accel << " ray " << i;
        }
        EXPECT_GT(both, rays.size() / 3) << accel;
        // Only rays through an edge or a vertex (within the rounding of two different tests) may differ.
        EXPECT_LE(disagree, rays.size() / 2000) << accel;
    }
}

TEST(Terrain, BadValuesNameTheirKey) {
    const auto error = testing::objectError;
    EXPECT_NE(error(R"({"type": "heightfield", "resolution": 0})").find("objects[0].resolution"), std::string::npos);
    EXPECT_NE(error(R"({"type": "heightfield", "octaves": 40})").find("objects[0].octaves"), std::string::npos);
    EXPECT_NE(error(R"({"type": "generated", "shape": "terrain", "height": -1})").find("objects[0].height"), std::string::npos);
    EXPECT_NE(error(R"({"type": "heightfield", "radius": 1})").find("radius"), std::string::npos);
    EXPECT_NE(error(R"({"type": "heightfield", "lacunarity": 1000, "octaves": 16})").find("lacunarity"), std::string::npos);
    EXPECT_NE(error(R"({"type": "heightfield", "roughness": -40})").find("roughness"), std::string::npos);
}

} // namespace
} // namespace wideray
