// pbrt scene files: the tokenizer, every directive wideray reads, its errors (each with file:line),
// what it reports and skips, the camera's handedness, a small scene rendered against a stored
// reference, and the shared Bitterli scenes.
#include <fstream>

#include <fmt/core.h>
#include <gtest/gtest.h>

#include "backends/wideray_structure.h"
#include "core/error.h"
#include "io/image_io.h"
#include "io/mesh_framing.h"
#include "io/pbrt_parser.h"
#include "io/pbrt_tokenizer.h"
#include "render/image_difference.h"
#include "render/renderer.h"
#include "temp_dir.h"
#include "test_data.h"

namespace wideray {
namespace {

const std::filesystem::path kData = std::filesystem::path(WIDERAY_SOURCE_DIR) / "tests/data/pbrt";

SceneDescription parse(const std::string& text) { return parsePbrt(text, "test.pbrt"); }

/// The world block of a scene with a camera whose frame is right-handed, so that the import keeps the
/// world as it is (ImagesAreNotMirrored).
SceneDescription world(const std::string& body) {
    return parse("Scale -1 1 1\nLookAt 0 0 -5  0 0 0  0 1 0\nCamera \"perspective\" \"float fov\" 40\nWorldBegin\n" + body + "\n");
}

void expectError(const std::string& text, const std::string& message) {
    try {
        parse(text);
        ADD_FAILURE() << "no error for:\n" << text;
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find(message), std::string::npos) << e.what();
    }
}

TEST(PbrtTokenizer, TokensWithTheirLines) {
    PbrtTokenizer t("Shape \"sphere\" # a comment [ ]\n  \"float radius\" [ 2.5e-1 -3 ]", "x.pbrt");
    using K = PbrtToken::Kind;
    const std::vector<std::pair<K, std::string>> expected = {{K::Identifier, "Shape"}, {K::String, "sphere"},
                                                             {K::String, "float radius"}, {K::OpenBracket, "["},
                                                             {K::Number, "2.5e-1"}, {K::Number, "-3"},
                                                             {K::CloseBracket, "]"}};
    for (const auto& [kind, text] : expected) {
        const PbrtToken token = t.next();
        EXPECT_EQ(token.kind, kind) << text;
        EXPECT_EQ(token.text, text);
        EXPECT_EQ(token.line, text == "Shape" || text == "sphere" ? 1 : 2) << text;
    }
    EXPECT_EQ(t.next().kind, K::End);
    PbrtTokenizer open("Shape\n\"sphere", "x.pbrt");
    open.next();
    EXPECT_THROW(open.next(), InputError);
    try {
        PbrtTokenizer bad("\n\n  @", "x.pbrt");
        bad.next();
    } catch (const InputError& e) {
        EXPECT_STREQ(e.what(), "x.pbrt:line 3: unexpected character '@'");
    }
}

TEST(PbrtParser, CameraFilmSamplerIntegrator) {
    const SceneDescription s = parse(R"(
        LookAt 1 2 3  1 2 4  0 1 0
        Camera "perspective" "float fov" [ 30 ] "float lensradius" 0.1 "float focaldistance" 4
        Film "image" "integer xresolution" 200 "integer yresolution" 400
        Sampler "sobol" "integer pixelsamples" [ 9 ]
        Integrator "whitted" "integer maxdepth" [ 3 ]
        WorldBegin
        WorldEnd)");
    EXPECT_EQ(s.image.width, 200);
    EXPECT_EQ(s.image.height, 400);
    EXPECT_EQ(s.image.samplesPerPixel, 9);
    EXPECT_EQ(s.render.integrator, Integrator::Whitted);
    EXPECT_EQ(s.render.maxDepth, 3);
    EXPECT_NEAR(s.camera.position.x, 1.0f, 1e-5f);
    EXPECT_NEAR(s.camera.position.z, 3.0f, 1e-5f);
    EXPECT_NEAR(glm::normalize(s.camera.lookAt - s.camera.position).z, 1.0f, 1e-5f);
    // pbrt's fov spans the shorter side, here the width: the vertical one is wider.
    EXPECT_NEAR(s.camera.fovY, glm::degrees(2 * std::atan(2 * std::tan(glm::radians(15.0f)))), 1e-3f);
    EXPECT_FLOAT_EQ(s.camera.aperture, 0.1f);
    EXPECT_FLOAT_EQ(s.camera.focusDistance, 4.0f);
}

TEST(PbrtParser, ImagesAreNotMirrored) {
    // pbrt's camera frame is left-handed: with this LookAt, +x is on the image's right. Whatever the
    // import does to the world, what pbrt shows on the right must be on the right of our image.
    for (const char* transform : {"LookAt 0 0 0  0 0 1  0 1 0", "Scale -1 1 1\nLookAt 0 0 0  0 0 1  0 1 0"}) {
        const SceneDescription s = parse(std::string(transform) + R"(
            Camera "perspective"
            WorldBegin
            AttributeBegin
              Translate 1 0 5
              Shape "sphere" "float radius" 0.5
            AttributeEnd)");
        ASSERT_EQ(s.analytics.size(), 1u);
        const glm::vec3 center(s.analytics[0].transform[3]);
        const glm::vec3 forward = glm::normalize(s.camera.lookAt - s.camera.position);
        const glm::vec3 right = glm::cross(forward, s.camera.up);
        const bool pbrtRight = std::string(transform).find("Scale") == std::string::npos;
        EXPECT_EQ(glm::dot(center - s.camera.position, right) > 0.0f, pbrtRight) << transform;
    }
}

TEST(PbrtParser, ShapesMaterialsAndTransforms) {
    const SceneDescription s = world(R"(
        MakeNamedMaterial "gold" "string type" "metal" "spectrum eta" "metal-Au-eta" "spectrum k" "metal-Au-k"
            "float roughness" 0.01 "bool remaproughness" "false"
        AttributeBegin
          Translate 1 0 0
          Scale 2 2 2
          NamedMaterial "gold"
          Shape "trianglemesh" "integer indices" [0 1 2] "point P" [0 0 0 1 0 0 0 1 0] "float uv" [0 0 1 0 0 1]
        AttributeEnd
        Material "plastic" "rgb Kd" [0.1 0.2 0.3] "rgb Ks" [0.5 0.5 0.5] "float roughness" 0.1 "bool remaproughness" "false"
        Shape "trianglemesh" "point P" [0 0 0 1 0 0 0 1 0]
        Material "glass" "float index" 1.33
        Shape "sphere" "float radius" 2
        Material "mirror"
        Shape "sphere"
        AttributeBegin
          Translate 0 0 2
          Shape "cylinder" "float radius" 0.5 "float zmin" 0 "float zmax" 4
        AttributeEnd)");
    ASSERT_EQ(s.meshes.size(), 2u);
    ASSERT_EQ(s.instances.size(), 2u);
    EXPECT_EQ(s.meshes[0].uvs.size(), 3u);
    const glm::vec3 moved = glm::vec3(s.instances[0].transform * glm::vec4(1, 0, 0, 1));
    EXPECT_NEAR(moved.x, 3.0f, 1e-5f);
    const Material& gold = s.materials[s.instances[0].material];
    EXPECT_EQ(gold.name, "gold");
    EXPECT_EQ(gold.type, MaterialType::Conductor);
    EXPECT_NEAR(gold.roughness, 0.1f, 1e-5f);  // alpha 0.01 = roughness^2
    EXPECT_GT(gold.k.x, 1.0f);
    const Material& plastic = s.materials[s.instances[1].material];
    EXPECT_EQ(plastic.type, MaterialType::Plastic);
    EXPECT_EQ(plastic.color, glm::vec3(0.1f, 0.2f, 0.3f));
    EXPECT_FLOAT_EQ(plastic.specular, 0.5f);
    EXPECT_NEAR(plastic.shininess, 198.0f, 1e-2f);  // 2 / alpha^2 - 2
    ASSERT_EQ(s.analytics.size(), 3u);
    // The cylinder's axis runs along z from 2 to 6, radius 0.5.
    const AnalyticObject& tube = s.analytics[2];
    EXPECT_EQ(tube.shape, AnalyticShape::Cylinder);
    EXPECT_FALSE(tube.capped);
    const glm::vec3 top(tube.transform * glm::vec4(0, 1, 0, 1)), rim(tube.transform * glm::vec4(1, 0, 0, 1));
    EXPECT_NEAR(top.z, 6.0f, 1e-5f);
    EXPECT_NEAR(glm::distance(rim, glm::vec3(0, 0, 4)), 0.5f, 1e-5f);
    EXPECT_EQ(s.materials[s.analytics[0].material].type, MaterialType::Dielectric);
    EXPECT_FLOAT_EQ(s.materials[s.analytics[0].material].ior, 1.33f);
    EXPECT_NEAR(s.analytics[0].transform[0][0], 2.0f, 1e-6f);
    EXPECT_EQ(s.materials[s.analytics[1].material].type, MaterialType::Mirror);
    EXPECT_TRUE(s.warnings.empty()) << s.warnings.front();
}

TEST(PbrtParser, LightsAndTheirEmittingSide) {
    const SceneDescription s = world(R"(
        LightSource "point" "rgb I" [1 2 3] "point from" [0 4 0]
        LightSource "distant" "point from" [0 1 0] "point to" [0 0 0] "rgb L" [2 2 2]
        LightSource "infinite" "rgb L" [0.1 0.2 0.3]
        AttributeBegin
          AreaLightSource "diffuse" "rgb L" [5 5 5]
          Shape "trianglemesh" "integer indices" [0 1 2 0 2 3] "point P" [0 2 0 1 2 0 1 2 1 0 2 1] "normal N" [0 -1 0 0 -1 0 0 -1 0 0 -1 0]
        AttributeEnd
        AttributeBegin
          AreaLightSource "diffuse" "rgb L" [1 1 1]
          Translate 0 3 0
          Shape "sphere" "float radius" 0.25
        AttributeEnd)");
    ASSERT_EQ(s.lights.size(), 4u);
    EXPECT_EQ(s.lights[0].type, LightType::Point);
    EXPECT_EQ(s.lights[0].color, glm::vec3(1, 2, 3));
    EXPECT_EQ(s.lights[1].type, LightType::Directional);
    EXPECT_NEAR(s.lights[1].direction.y, -1.0f, 1e-6f);
    EXPECT_EQ(s.background, glm::vec3(0.1f, 0.2f, 0.3f));
    const Light& quad = s.lights[2];
    EXPECT_EQ(quad.type, LightType::Quad);
    EXPECT_EQ(quad.color, glm::vec3(5.0f));
    EXPECT_LT(glm::cross(quad.edgeU, quad.edgeV).y, 0.0f);  // facing its normals, down
    EXPECT_NEAR(glm::length(glm::cross(quad.edgeU, quad.edgeV)), 1.0f, 1e-5f);
    EXPECT_EQ(s.lights[3].type, LightType::Sphere);
    EXPECT_FLOAT_EQ(s.lights[3].radius, 0.25f);
    EXPECT_TRUE(s.meshes.empty());  // lights are not also geometry
}

TEST(PbrtParser, AreaLightsOnTrianglesAndTwoSided) {
    // A fan of three triangles wound toward +y: three triangle lights facing up; two-sided, six, in
    // opposite pairs. A mesh of 40 triangles stays a mesh, not emitting, and says so.
    const std::string fan = R"(Shape "trianglemesh" "integer indices" [0 1 2 0 2 3 0 3 4]
          "point P" [0 0 0  0 0 1  1 0 1  1 0 0  0.5 0 -1])";
    const SceneDescription s = world("AttributeBegin\nAreaLightSource \"diffuse\" \"rgb L\" [2 2 2]\n" + fan +
                                     "\nAttributeEnd\nAttributeBegin\nAreaLightSource \"diffuse\" \"rgb L\" [1 1 1] \"bool twosided\" true\n" +
                                     fan + "\nAttributeEnd");
    ASSERT_EQ(s.lights.size(), 9u);
    float area = 0;
    for (int i = 0; i < 3; ++i) {
        const Light& light = s.lights[size_t(i)];
        EXPECT_EQ(light.type, LightType::Triangle);
        EXPECT_EQ(light.color, glm::vec3(2.0f));
        const glm::vec3 n = glm::cross(light.edgeU, light.edgeV);
        EXPECT_GT(n.y, 0.0f) << i;  // pbrt's winding: (p0 - p2) x (p1 - p2) = +y, mirrored world aside
        area += 0.5f * glm::length(n);
    }
    EXPECT_NEAR(area, 1.5f, 1e-5f);
    for (int i = 3; i < 9; i += 2)
        EXPECT_LT(glm::dot(glm::cross(s.lights[size_t(i)].edgeU, s.lights[size_t(i)].edgeV),
                           glm::cross(s.lights[size_t(i + 1)].edgeU, s.lights[size_t(i + 1)].edgeV)),
                  0.0f);
    EXPECT_TRUE(s.meshes.empty());
    std::string indices, points;
    for (int i = 0; i < 40; ++i) {
        indices += fmt::format("{} {} {} ", 3 * i, 3 * i + 1, 3 * i + 2);
        points += fmt::format("{} 0 0  {} 0 1  {} 1 0  ", i, i, i);
    }
    const SceneDescription big = world("AreaLightSource \"diffuse\"\nShape \"trianglemesh\" \"integer indices\" [" + indices +
                                       "] \"point P\" [" + points + "]");
    EXPECT_TRUE(big.lights.empty());
    ASSERT_EQ(big.meshes.size(), 1u);
    ASSERT_EQ(big.warnings.size(), 1u);
    EXPECT_NE(big.warnings[0].find("more than 32 triangles"), std::string::npos) << big.warnings[0];
}

TEST(PbrtParser, ObjectInstancesAndIncludes) {
    TempDir dir;
    std::ofstream(dir.path() / "part.pbrt") << "ObjectBegin \"tri\"\nShape \"trianglemesh\" \"point P\" [0 0 0 1 0 0 0 1 0]\nObjectEnd\n";
    const SceneDescription s = parsePbrt(R"(Camera "perspective"
        WorldBegin
        Include "part.pbrt"
        ObjectInstance "tri"
        Translate 5 0 0
        ObjectInstance "tri")",
                                         dir.path() / "main.pbrt");
    ASSERT_EQ(s.meshes.size(), 1u);
    ASSERT_EQ(s.instances.size(), 2u);
    EXPECT_EQ(s.instances[1].mesh, 0u);
    // Mirrored (see ImagesAreNotMirrored) or not, the two copies are 5 apart.
    EXPECT_NEAR(glm::distance(glm::vec3(s.instances[0].transform[3]), glm::vec3(s.instances[1].transform[3])), 5.0f, 1e-5f);
}

TEST(PbrtParser, UnsupportedInputIsReportedOnceWithItsLine) {
    const SceneDescription s = world(R"(PixelFilter "gaussian"
PixelFilter "box"
Shape "curve" "point P" [0 0 0 1 1 1 2 2 2 3 3 3]
Material "matte" "float sigma" 20 "texture bumpmap" "nothing"
Shape "sphere")");
    const std::vector<std::string> expected = {
        "test.pbrt:line 5: PixelFilter is not supported; skipped",
        "test.pbrt:line 7: Shape \"curve\" is not supported; skipped",
        "test.pbrt:line 8: Material \"matte\": parameter \"float sigma\" is not supported; ignored",
        "test.pbrt:line 8: Material \"matte\": parameter \"texture bumpmap\" is not supported; ignored"};
    EXPECT_EQ(s.warnings, expected);
    EXPECT_EQ(s.analytics.size(), 1u);
}

TEST(PbrtParser, ErrorsNameFileAndLine) {
    expectError("WorldBegin\nFrobnicate 1 2", "test.pbrt:line 2: unknown directive 'Frobnicate'");
    expectError("WorldBegin\nAttributeEnd", "test.pbrt:line 2: AttributeEnd without a matching begin");
    expectError("WorldBegin\n\nNamedMaterial \"nope\"", "test.pbrt:line 3: NamedMaterial \"nope\" was not defined");
    expectError("Translate 1 2", "test.pbrt:line 1: expected 3 numbers");
    expectError("WorldBegin\nShape \"trianglemesh\" \"integer indices\" [0 1 5] \"point P\" [0 0 0 1 0 0 0 1 0]",
                "test.pbrt:line 2: \"indices\"[2] is 5, but there are 3 vertices");
    expectError("WorldBegin\nShape \"sphere\" \"real radius\" 2", "test.pbrt:line 2: unknown parameter type 'real'");
    expectError("WorldBegin\nShape \"sphere\" \"float radius\" [ 1 2 ]", "test.pbrt:line 2: \"float radius\" must be one number");
    expectError("WorldBegin\nInclude \"missing.pbrt\"", "test.pbrt:line 2: Include: cannot open");
    expectError("WorldBegin\nMaterial \"matte\" \"texture Kd\" \"undefined\"", "test.pbrt:line 2: \"texture Kd\" names no texture");
    expectError("Film \"image\" \"integer xresolution\" [ 0 ]", "test.pbrt:line 1: Film \"xresolution\" must be one number from 1 to 65536");
    expectError("WorldBegin\nShape \"sphere\" \"float radius\" [ 1", "'[' not closed");
    // Found by review, kept as regressions: numbers that are not finite floats, directories as files,
    // objects that instance objects (an object could grow by copies of itself).
    expectError("WorldBegin\nShape \"sphere\" \"float radius\" [ -nan ]", "test.pbrt:line 2: '-nan' is not a finite 32-bit float");
    expectError("Film \"image\" \"integer xresolution\" [ 1e39 ]", "test.pbrt:line 1: '1e39' is not a finite 32-bit float");
    expectError("WorldBegin\nInclude \"" + kData.string() + "\"", "test.pbrt:line 2: Include: cannot open " + kData.string() + " (not a regular file)");
    expectError("WorldBegin\nObjectBegin \"a\"\nShape \"trianglemesh\" \"integer indices\" [0 1 2] \"point P\" [0 0 0 1 0 0 0 1 0]\n"
                "ObjectEnd\nObjectBegin \"b\"\nObjectInstance \"a\"",
                "test.pbrt:line 6: ObjectInstance \"a\" inside ObjectBegin (nested instancing is not supported)");
    expectError("WorldBegin\nObjectBegin \"a\"\nObjectBegin \"b\"", "test.pbrt:line 3: ObjectBegin \"b\" inside another ObjectBegin");
}

Image renderScene(const SceneDescription& scene) {
    auto geometry = std::make_shared<const SceneGeometry>(scene);
    std::unique_ptr<Tracer> tracer = buildWideBvh(geometry, {})->tracer({});
    RenderStats stats;
    return render(scene, *tracer, {}, stats);
}

TEST(PbrtRender, SmallSceneMatchesItsReference) {
    // Rendered by `wideray render tests/data/pbrt/box.pbrt -o tests/data/pbrt/box_reference.exr`
    // (48x32, 4 samples per pixel, as the file says). Other ISAs may trace a few paths differently.
    const SceneDescription scene = loadSceneOrMesh(kData / "box.pbrt");
    EXPECT_TRUE(scene.warnings.empty()) << scene.warnings.front();
    const Image image = renderScene(scene);
    const Image reference = readImage(kData / "box_reference.exr", false);
    ASSERT_EQ(image.width, 48);
    ASSERT_EQ(image.height, 32);
    const ImageDifference d = compareImages(image, reference, 0.05f);
    EXPECT_LT(d.meanAbsolute, 0.01);
    EXPECT_LT(double(d.pixelsOver), 0.05 * double(d.pixels));
    // The red wall is on the left and the green one on the right, as pbrt shows them.
    const float* left = image.at(12, 16);
    const float* right = image.at(36, 16);
    EXPECT_GT(left[0], 2 * left[1]);
    EXPECT_GT(right[1], 2 * right[0]);
}

TEST(PbrtRender, SharedBitterliScenes) {
    const auto shared = sharedScenesDir();
    if (!shared) GTEST_SKIP() << "../shared/scenes not found";
    for (const char* folder : {"bitterli-coffee-maker", "bitterli-country-kitchen"}) {
        const std::filesystem::path file = *shared / folder / "scene.pbrt";
        if (!std::filesystem::exists(file)) continue;
        SceneDescription scene = loadSceneOrMesh(file);
        EXPECT_GT(scene.meshes.size(), 10u) << folder;
        EXPECT_GE(scene.lights.size(), 3u) << folder;  // their quad area lights
        EXPECT_EQ(scene.render.integrator, Integrator::Path);
        // Every shape and light of theirs is one wideray has (their missing textures are reported).
        for (const std::string& w : scene.warnings)
            EXPECT_TRUE(w.find("Shape") == std::string::npos && w.find("Light") == std::string::npos) << w;
        if (std::string(folder) == "bitterli-country-kitchen") {
            EXPECT_EQ(scene.image.width, 1280);
            // The camera of its scene.pbrt, as scenes/country_kitchen.json has it.
            EXPECT_NEAR(scene.camera.position.x, 1.211005f, 1e-4f);
            EXPECT_NEAR(scene.camera.position.y, 1.804751f, 1e-4f);
            EXPECT_NEAR(scene.camera.position.z, 3.852394f, 1e-4f);
        }
        scene.image = {32, 18, 1};
        const Image image = renderScene(scene);
        double sum = 0;
        for (float c : image.pixels) sum += c;
        EXPECT_GT(sum / double(image.pixels.size()), 0.01) << folder << " renders black";
    }
}

} // namespace
} // namespace wideray
