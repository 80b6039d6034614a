// Environment maps: where directions fall in the image for both mappings, the lookup, and what the
// camera sees of a map given in a JSON scene and in a pbrt scene (pbrt's handedness included).
#include <cmath>
#include <fstream>
#include <random>

#include <glm/gtc/constants.hpp>
#include <gtest/gtest.h>

#include "backends/wideray_structure.h"
#include "core/error.h"
#include "io/image_io.h"
#include "io/mesh_framing.h"
#include "io/scene_parser.h"
#include "render/renderer.h"
#include "shading/environment.h"
#include "temp_dir.h"

namespace wideray {
namespace {

void expectUv(EnvironmentMapping mapping, glm::vec3 d, glm::vec2 uv) {
    const glm::vec2 got = environmentUv(mapping, d);
    EXPECT_NEAR(got.x, uv.x, 1e-5f) << d.x << " " << d.y << " " << d.z;
    EXPECT_NEAR(got.y, uv.y, 1e-5f) << d.x << " " << d.y << " " << d.z;
}

TEST(Environment, LatLongDirections) {
    using M = EnvironmentMapping;
    expectUv(M::LatLong, {0, 0, 1}, {0.0f, 0.0f});     // +z: the top row
    expectUv(M::LatLong, {1, 0, 0}, {0.0f, 0.5f});     // +x: the left edge, on the horizon
    expectUv(M::LatLong, {0, 2, 0}, {0.25f, 0.5f});    // +y a quarter of the way round (need not be unit)
    expectUv(M::LatLong, {-1, 0, 0}, {0.5f, 0.5f});
    expectUv(M::LatLong, {0, -1, 0}, {0.75f, 0.5f});
    expectUv(M::LatLong, {1, 0, -1}, {0.0f, 0.75f});   // 45 degrees below the horizon
}

TEST(Environment, EqualAreaDirectionsAndAreas) {
    using M = EnvironmentMapping;
    expectUv(M::EqualArea, {0, 0, 1}, {0.5f, 0.5f});   // +z: the center
    expectUv(M::EqualArea, {1, 0, 0}, {1.0f, 0.5f});   // the horizon: the diamond through the edge midpoints
    expectUv(M::EqualArea, {0, -1, 0}, {0.5f, 0.0f});
    expectUv(M::EqualArea, {0, 0, -1}, {1.0f, 1.0f});  // -z: a corner
    // Equal area: uniform directions fill an 8 x 8 grid of cells evenly.
    std::mt19937 rng(7);
    std::normal_distribution<float> gauss;
    std::vector<int> cells(64, 0);
    const int n = 256000;
    for (int i = 0; i < n; ++i) {
        const glm::vec2 uv = environmentUv(M::EqualArea, {gauss(rng), gauss(rng), gauss(rng)});
        ++cells[size_t(std::min(int(uv.y * 8), 7) * 8 + std::min(int(uv.x * 8), 7))];
    }
    for (int c : cells) EXPECT_NEAR(double(c), n / 64.0, 0.06 * n / 64.0);
}

TEST(Environment, LookupIsBilinearAndScaled) {
    // Two columns, black (center at u = 0.25) and white (u = 0.75): +y (u = 0.25) sees black, -y
    // white, -x (u = 0.5) half of each.
    EnvironmentMap map;
    auto image = std::make_shared<Image>(2, 1, 3);
    for (int c = 0; c < 3; ++c) image->at(1, 0)[c] = 1.0f;
    map.image = image;
    map.scale = glm::vec3(2.0f, 2.0f, 4.0f);
    EXPECT_NEAR(environmentRadiance(map, {0, 1, 0}).x, 0.0f, 1e-5f);
    EXPECT_NEAR(environmentRadiance(map, {0, -1, 0}).x, 2.0f, 1e-5f);
    EXPECT_NEAR(environmentRadiance(map, {-1, 0, 0}).z, 2.0f, 1e-5f);
    // Longitude wraps: +x lies between the last column and the first.
    EXPECT_NEAR(environmentRadiance(map, {1, 0, 0}).y, 1.0f, 1e-5f);
}

/// A lat-long map whose four quarters of longitude are red, green, blue and white (from +x toward +y).
std::filesystem::path writeQuarters(const std::filesystem::path& folder) {
    Image image(64, 32, 3);
    const glm::vec3 colors[4] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 1}};
    for (int y = 0; y < 32; ++y)
        for (int x = 0; x < 64; ++x)
            for (int c = 0; c < 3; ++c) image.at(x, y)[c] = colors[x / 16][c];
    const std::filesystem::path file = folder / "quarters.exr";
    writeImage(image, file, false);
    return file;
}

/// The color of pixel (x, 4) of a 9 x 9 render of `scene`.
glm::vec3 pixelColor(SceneDescription scene, int x = 4) {
    scene.image = {9, 9, 1};
    auto geometry = std::make_shared<const SceneGeometry>(scene);
    std::unique_ptr<Tracer> tracer = buildWideBvh(geometry, {})->tracer({});
    RenderStats stats;
    const Image image = render(scene, *tracer, {}, stats);
    const float* p = image.at(x, 4);
    return {p[0], p[1], p[2]};
}

TEST(Environment, JsonSceneShowsItsMapWhereRaysLeave) {
    TempDir dir;
    writeQuarters(dir.path());
    // The camera looks along +x+y (longitude 45 degrees: red) and, after the map is turned a quarter
    // about z, along the same world direction it sees the quarter before red: white.
    auto scene = [&](const std::string& transform) {
        return parseScene(R"({"camera": {"position": [0, 0, 0], "look_at": [1, 1, 0], "up": [0, 0, 1], "fov": 10},
            "environment": {"file": "quarters.exr", "scale": 0.5)" + transform + R"(},
            "objects": [{"type": "sphere", "center": [0, 0, -50], "radius": 1}]})",
                          dir.path() / "scene.json");
    };
    const SceneDescription plain = scene("");
    ASSERT_TRUE(plain.environment);
    EXPECT_EQ(plain.environment->mapping, EnvironmentMapping::LatLong);
    const glm::vec3 red = pixelColor(plain);
    EXPECT_NEAR(red.r, 0.5f, 1e-3f);
    EXPECT_NEAR(red.g, 0.0f, 1e-3f);
    const SceneDescription turned = scene(R"(, "transform": {"rotate": {"axis": [1, 2, 3], "degrees": 37}}, "mapping": "latlong")");
    const glm::vec3 white = pixelColor(scene(R"(, "transform": {"rotate": {"axis": [0, 0, 1], "degrees": 90}})"));
    EXPECT_NEAR(white.r, 0.5f, 1e-3f);
    EXPECT_NEAR(white.b, 0.5f, 1e-3f);
    // Written and read back, the map is the same, bit for bit also when turned.
    for (const SceneDescription* original : {&plain, &turned}) {
        const SceneDescription again = parseScene(writeScene(*original), dir.path() / "again.json");
        ASSERT_TRUE(again.environment);
        EXPECT_EQ(again.environment->toWorld, original->environment->toWorld);
        EXPECT_EQ(again.environment->fromWorld, original->environment->fromWorld);
        EXPECT_EQ(again.environment->scale, original->environment->scale);
        EXPECT_EQ(again.environment->mapping, original->environment->mapping);
    }
    // Errors name the key.
    auto expectError = [&](const std::string& environment, const std::string& where, const std::string& what) {
        try {
            parseScene(R"({"environment": )" + environment + R"(, "objects": []})", dir.path() / "bad.json");
            ADD_FAILURE() << environment << " was accepted";
        } catch (const InputError& e) {
            EXPECT_NE(std::string(e.what()).find(where), std::string::npos) << e.what();
            EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
        }
    };
    expectError(R"({"file": "quarters.exr", "mapping": "cube"})", "environment.mapping", "cube");
    expectError(R"({"file": "quarters.exr", "mapping": "equal_area"})", "environment.mapping", "square");
}

TEST(Environment, PbrtInfiniteLightKeepsPbrtsSides) {
    // pbrt looks along +x+y (longitude 45 degrees: red) with +z up; the right of its image is toward
    // -x+y (camera +x is up x direction), where the 120 degree view reaches longitude 102 (green), and
    // the left reaches -12 (white). Its camera frame is left-handed, so the import mirrors the world,
    // and the map must turn with it.
    TempDir dir;
    writeQuarters(dir.path());
    const std::filesystem::path file = dir.path() / "sky.pbrt";
    std::ofstream(file) << R"(LookAt 0 0 0  1 1 0  0 0 1
Camera "perspective" "float fov" 120
WorldBegin
LightSource "infinite" "string filename" "quarters.exr"
AttributeBegin
  Translate 0 0 -50
  Shape "sphere" "float radius" 1
AttributeEnd
)";
    const SceneDescription scene = loadSceneOrMesh(file);
    ASSERT_TRUE(scene.environment);
    const glm::vec3 center = pixelColor(scene), right = pixelColor(scene, 8), left = pixelColor(scene, 0);
    EXPECT_GT(center.r, 0.9f);
    EXPECT_LT(center.g + center.b, 0.1f);
    EXPECT_GT(right.g, 0.9f);
    EXPECT_LT(right.r + right.b, 0.1f);
    EXPECT_GT(left.r + left.g + left.b, 2.7f);
}

TEST(Environment, PbrtV3MapnameIsScaledByItsRadiance) {
    // pbrt-v3 names the image "mapname" and multiplies it by L and scale; of several infinite lights
    // the last one lights the scene, with a warning.
    TempDir dir;
    writeQuarters(dir.path());
    const std::filesystem::path file = dir.path() / "sky.pbrt";
    std::ofstream(file) << R"(LookAt 0 0 0  1 1 0  0 0 1
Camera "perspective" "float fov" 10
WorldBegin
LightSource "infinite" "rgb L" [0 1 0]
LightSource "infinite" "string mapname" "quarters.exr" "rgb L" [0.5 0.25 1] "float scale" 2
AttributeBegin
  Translate 0 0 -50
  Shape "sphere" "float radius" 1
AttributeEnd
)";
    const SceneDescription scene = loadSceneOrMesh(file);
    ASSERT_TRUE(scene.environment);
    const glm::vec3 center = pixelColor(scene);
    EXPECT_NEAR(center.r, 1.0f, 1e-3f);
    EXPECT_NEAR(center.g + center.b, 0.0f, 1e-3f);
    ASSERT_EQ(scene.warnings.size(), 1u);
    EXPECT_NE(scene.warnings[0].find(":line 5:"), std::string::npos) << scene.warnings[0];
    EXPECT_NE(scene.warnings[0].find("several infinite lights"), std::string::npos) << scene.warnings[0];
}

} // namespace
} // namespace wideray
