// Scene files: parsing, the writeScene round trip, error messages, and the procedural meshes.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <string>
#include <tuple>

#include <gtest/gtest.h>
#include <unistd.h>

#include "core/error.h"
#include "io/mesh_generators.h"
#include "geometry/triangle_geometry.h"
#include "io/scene_parser.h"
#include "temp_dir.h"

namespace wideray {
namespace {

namespace fs = std::filesystem;

const fs::path kRepo = fs::path(__FILE__).parent_path().parent_path();
const fs::path kSceneFile = "memory/test_scene.json";

SceneDescription parse(const std::string& text) { return parseScene(text, kSceneFile); }

/// Parses `text`, expecting an InputError whose message names the scene file, `location` and `fragment`.
void expectError(const std::string& text, const std::string& location, const std::string& fragment) {
    try {
        parse(text);
        ADD_FAILURE() << "no error for:\n" << text;
    } catch (const InputError& e) {
        const std::string what = e.what();
        const std::string prefix = kSceneFile.string() + (location.empty() ? "" : ":" + location) + ": ";
        EXPECT_EQ(what.rfind(prefix, 0), 0u) << what;
        EXPECT_EQ(e.location(), location) << what;
        EXPECT_NE(what.find(fragment), std::string::npos) << what;
    }
}

/// A scene of one sphere, with `extra` spliced in among the top-level keys.
std::string sceneWith(const std::string& extra) {
    return "{" + extra + (extra.empty() ? "" : ",") +
           R"("objects": [{"type": "sphere", "center": [0, 0, 0], "radius": 1}]})";
}

/// A scene with only the given objects (a JSON array).
std::string sceneOfObjects(const std::string& objects) { return R"({"objects": )" + objects + "}"; }

void writeFile(const fs::path& path, const std::string& text) {
    fs::create_directories(path.parent_path());
    std::ofstream(path) << text;
}

const char* kTriangleObj = "mtllib tri.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\n"
                           "usemtl red\nf 1 2 3\nusemtl blue\nf 2 4 3\n";
const char* kTriangleMtl = "newmtl red\nKd 0.9 0.1 0.1\nnewmtl blue\nKd 0.1 0.1 0.9\n";

const Material* findMaterial(const SceneDescription& scene, const std::string& name) {
    for (const Material& m : scene.materials)
        if (m.name == name) return &m;
    return nullptr;
}

// ---- valid scenes

TEST(SceneParser, DefaultSceneParses) {
    const SceneDescription scene = loadScene(kRepo / "scenes/default.json");
    EXPECT_EQ(scene.image.width, 640);
    EXPECT_EQ(scene.image.height, 480);
    EXPECT_EQ(scene.image.samplesPerPixel, 1);
    ASSERT_EQ(scene.lights.size(), 2u);
    EXPECT_EQ(scene.lights[0].type, LightType::Point);
    EXPECT_EQ(scene.lights[1].type, LightType::Quad);
    EXPECT_EQ(scene.lights[1].samples, 4);
    EXPECT_EQ(scene.spheres.size(), 1u);
    EXPECT_EQ(scene.instances.size(), 8u);  // 5 walls, 2 boxes, 1 torus
    ASSERT_NE(findMaterial(scene, "red"), nullptr);
    ASSERT_NE(findMaterial(scene, "green"), nullptr);
    const TriangleMesh world = flattenTriangles(scene);
    EXPECT_EQ(world.triangleCount(), 5 * 2 + 2 * 12 + 2 * 48 * 24u);
    for (const glm::vec3& p : world.positions) {  // everything is inside the room
        EXPECT_GE(p.y, -1e-5f);
        EXPECT_LE(std::abs(p.x), 1.0f + 1e-5f);
    }
}

TEST(SceneParser, BunnySceneParses) {
    // The scene names the bunny by a path relative to itself, in the shared folder beside the repository.
    if (!std::filesystem::exists(kRepo / "../shared/scenes/stanford-bunny/bun_zipper.ply"))
        GTEST_SKIP() << "needs ../shared/scenes beside the repository";
    const SceneDescription scene = loadScene(kRepo / "scenes/bunny.json");
    ASSERT_EQ(scene.meshes.size(), 2u);
    EXPECT_EQ(scene.meshes[0].triangleCount() + scene.meshes[0].droppedDegenerate, 69451u);
    EXPECT_EQ(scene.meshes[0].positions.size(), 35947u);
}

TEST(SceneParser, DefaultsApplyToOmittedSettings) {
    const SceneDescription scene = parse(sceneWith(""));
    const Camera defaults;
    EXPECT_EQ(scene.camera.position, defaults.position);
    EXPECT_EQ(scene.camera.fovY, defaults.fovY);
    EXPECT_EQ(scene.image.width, 640);
    EXPECT_EQ(scene.image.height, 480);
    EXPECT_EQ(scene.image.samplesPerPixel, 1);
    EXPECT_EQ(scene.background, glm::vec3(0.0f));
    ASSERT_EQ(scene.materials.size(), 1u);  // the sphere has no material: "default" is created
    EXPECT_EQ(scene.materials[0].name, "default");
    EXPECT_EQ(scene.materials[0].color, glm::vec3(0.8f));
}

TEST(SceneParser, CommentsAreAllowed) {
    const SceneDescription scene = parse("// a comment\n" + sceneWith(R"("image": {"spp": 4 /* four */})"));
    EXPECT_EQ(scene.image.samplesPerPixel, 4);
}

TEST(SceneParser, RoundTripGivesEqualScene) {
    TempDir dir;
    writeFile(dir.path() / "tri.obj", kTriangleObj);
    writeFile(dir.path() / "tri.mtl", kTriangleMtl);
    const std::string text = R"({
      "camera": {"position": [1, 2, 3.3], "look_at": [0.1, 0.2, 0.3], "up": [0, 0, 1], "fov": 33.3,
                 "aperture": 0.1, "focus_distance": 2.5},
      "image": {"width": 320, "height": 200, "spp": 8},
      "background": [0.1, 0.2, 0.3],
      "materials": {"white": {"type": "diffuse", "color": [0.7, 0.7, 0.7]},
                    "red": {"type": "diffuse", "color": [0.6, 0.05, 0.05]}},
      "lights": [{"type": "point", "position": [1, 2, 3], "color": [1, 0.5, 0.25], "intensity": 10},
                 {"type": "directional", "direction": [1, -1, 0], "intensity": 2},
                 {"type": "quad", "corner": [0, 2, 0], "edge_u": [0.5, 0, 0], "edge_v": [0, 0, 0.5], "samples": 16},
                 {"type": "sphere", "center": [0, 3, 0], "radius": 0.2, "intensity": 5, "samples": 9}],
      "meshes": {"ring": {"generate": "torus", "major_radius": 1, "minor_radius": 0.3,
                          "major_segments": 12, "minor_segments": 6}},
      "objects": [
        {"type": "instance", "mesh": "ring", "material": "white"},
        {"type": "instance", "mesh": "ring", "transform": {"scale": [1, 2, 3], "translate": [0.1, 0.2, 0.3]}},
        {"type": "mesh", "file": "tri.obj", "transform": {"rotate": {"axis": [1, 1, 0], "degrees": 33}}},
        {"type": "mesh", "file": "tri.obj", "material": "white"},
        {"type": "generated", "shape": "icosphere", "subdivisions": 1, "material": "red",
         "transform": {"scale": [-1, 1, 1]}},
        {"type": "triangles", "vertices": [[0, 0, 0], [1, 0, 0], [0, 1, 0]], "indices": [[0, 1, 2]],
         "normals": [[0, 0, 1], [0, 0, 1], [0, 0, 1]], "uvs": [[0, 0], [1, 0], [0, 1]]},
        {"type": "sphere", "center": [1, 1, 1], "radius": 0.5, "material": "red",
         "transform": {"scale": 2, "rotate": {"axis": [0, 1, 0], "degrees": 45}}}
      ]})";
    const SceneDescription first = parseScene(text, dir.path() / "scene.json");
    const std::string written = writeScene(first);
    const SceneDescription second = parseScene(written, "written.json");

    EXPECT_EQ(first.camera.position, second.camera.position);
    EXPECT_EQ(first.camera.lookAt, second.camera.lookAt);
    EXPECT_EQ(first.camera.up, second.camera.up);
    EXPECT_EQ(first.camera.fovY, second.camera.fovY);
    EXPECT_EQ(first.camera.aperture, second.camera.aperture);
    EXPECT_EQ(first.camera.focusDistance, second.camera.focusDistance);
    EXPECT_EQ(first.image.width, second.image.width);
    EXPECT_EQ(first.image.height, second.image.height);
    EXPECT_EQ(first.image.samplesPerPixel, second.image.samplesPerPixel);
    EXPECT_EQ(first.background, second.background);

    ASSERT_EQ(first.lights.size(), 4u);
    ASSERT_EQ(second.lights.size(), first.lights.size());
    for (size_t i = 0; i < first.lights.size(); ++i) {
        const Light &a = first.lights[i], &b = second.lights[i];
        EXPECT_EQ(a.type, b.type);
        EXPECT_EQ(a.color, b.color);
        EXPECT_EQ(a.intensity, b.intensity);
        EXPECT_EQ(a.position, b.position);
        EXPECT_EQ(a.direction, b.direction);
        EXPECT_EQ(a.edgeU, b.edgeU);
        EXPECT_EQ(a.edgeV, b.edgeV);
        EXPECT_EQ(a.radius, b.radius);
        EXPECT_EQ(a.samples, b.samples);
    }

    // white, red (which restyles the MTL's red), tri/blue from the MTL file, default for the triangle
    ASSERT_EQ(first.materials.size(), 4u);
    ASSERT_EQ(second.materials.size(), first.materials.size());
    for (size_t i = 0; i < first.materials.size(); ++i) {
        EXPECT_EQ(first.materials[i].name, second.materials[i].name);
        EXPECT_EQ(first.materials[i].type, second.materials[i].type);
        EXPECT_EQ(first.materials[i].color, second.materials[i].color);
    }

    ASSERT_EQ(second.meshes.size(), first.meshes.size());
    EXPECT_EQ(second.instances.size(), first.instances.size());
    const TriangleMesh a = flattenTriangles(first), b = flattenTriangles(second);
    EXPECT_GT(a.triangleCount(), 0u);
    EXPECT_EQ(a.positions, b.positions);
    EXPECT_EQ(a.normals, b.normals);
    EXPECT_EQ(a.uvs, b.uvs);
    EXPECT_EQ(a.triangles, b.triangles);
    EXPECT_EQ(a.faceMaterial, b.faceMaterial);

    ASSERT_EQ(second.spheres.size(), 1u);
    EXPECT_EQ(first.spheres[0].center, second.spheres[0].center);
    EXPECT_EQ(first.spheres[0].radius, second.spheres[0].radius);
    EXPECT_EQ(first.spheres[0].material, second.spheres[0].material);

    EXPECT_EQ(writeScene(second), written);
}

TEST(SceneParser, TransformScalesThenRotatesThenTranslates) {
    const SceneDescription scene = parse(sceneOfObjects(R"([{"type": "triangles",
        "vertices": [[1, 0, 0], [0, 1, 0], [0, 0, 1]], "indices": [[0, 1, 2]],
        "transform": {"translate": [10, 0, 0], "rotate": {"axis": [0, 0, 1], "degrees": 90}, "scale": 2}}])"));
    const TriangleMesh world = flattenTriangles(scene);
    ASSERT_EQ(world.positions.size(), 3u);
    // (1,0,0) scaled to (2,0,0), rotated to (0,2,0), translated to (10,2,0)
    EXPECT_NEAR(glm::distance(world.positions[0], glm::vec3(10, 2, 0)), 0.0f, 1e-5f);
    EXPECT_NEAR(glm::distance(world.positions[2], glm::vec3(10, 0, 2)), 0.0f, 1e-5f);
}

TEST(SceneParser, RotationListAppliesInOrder) {
    const SceneDescription scene = parse(sceneOfObjects(R"([{"type": "triangles",
        "vertices": [[1, 0, 0], [0, 1, 0], [0, 0, 1]], "indices": [[0, 1, 2]],
        "transform": {"rotate": [{"axis": [0, 0, 1], "degrees": 90}, {"axis": [1, 0, 0], "degrees": 90}]}}])"));
    const TriangleMesh world = flattenTriangles(scene);
    // (1,0,0) -> about z -> (0,1,0) -> about x -> (0,0,1)
    EXPECT_NEAR(glm::distance(world.positions[0], glm::vec3(0, 0, 1)), 0.0f, 1e-6f);
}

TEST(SceneParser, MatrixIsRowMajor) {
    const SceneDescription scene = parse(sceneOfObjects(R"([{"type": "triangles",
        "vertices": [[1, 0, 0], [0, 1, 0], [0, 0, 1]], "indices": [[0, 1, 2]],
        "transform": {"matrix": [2, 0, 0, 5,  0, 1, 0, 6,  0, 0, 1, 7,  0, 0, 0, 1]}}])"));
    EXPECT_EQ(flattenTriangles(scene).positions[0], glm::vec3(7, 6, 7));
}

TEST(SceneParser, SphereTransformMovesAndScales) {
    const SceneDescription scene = parse(sceneOfObjects(R"([{"type": "sphere", "center": [1, 0, 0], "radius": 0.5,
        "transform": {"scale": 2, "rotate": {"axis": [0, 0, 1], "degrees": 90}, "translate": [0, 0, 3]}}])"));
    ASSERT_EQ(scene.spheres.size(), 1u);
    EXPECT_NEAR(glm::distance(scene.spheres[0].center, glm::vec3(0, 2, 3)), 0.0f, 1e-5f);
    EXPECT_NEAR(scene.spheres[0].radius, 1.0f, 1e-6f);
}

TEST(SceneParser, NormalsUseInverseTransposeAndMirrorsKeepWinding) {
    const SceneDescription scene = parse(sceneOfObjects(R"([{"type": "triangles",
        "vertices": [[0, 0, 0], [1, 0, 0], [0, 1, 0]], "indices": [[0, 1, 2]],
        "normals": [[1, 1, 0], [0, 0, 1], [0, 0, 1]], "transform": {"scale": [-2, 1, 1]}}])"));
    const TriangleMesh world = flattenTriangles(scene);
    const glm::vec3 expected = glm::normalize(glm::vec3(-0.5f, 1.0f, 0.0f));
    EXPECT_NEAR(glm::distance(world.normals[0], expected), 0.0f, 1e-6f);
    // The mirror would flip the face to -z; the corners are swapped so it still faces +z like its normals.
    const glm::uvec3 t = world.triangles[0];
    const glm::vec3 face = glm::cross(world.positions[t.y] - world.positions[t.x], world.positions[t.z] - world.positions[t.x]);
    EXPECT_GT(face.z, 0.0f);
}

TEST(SceneParser, MeshesWithoutNormalsGetZeroNormalsWhenMixed) {
    const SceneDescription scene = parse(sceneOfObjects(R"([{"type": "generated", "shape": "cube"},
        {"type": "generated", "shape": "icosphere", "subdivisions": 0}])"));
    const TriangleMesh world = flattenTriangles(scene);
    ASSERT_EQ(world.normals.size(), world.positions.size());
    EXPECT_EQ(world.normals[0], glm::vec3(0.0f));
    EXPECT_NEAR(glm::length(world.normals[8]), 1.0f, 1e-6f);
}

TEST(SceneParser, RelativeMeshPathsResolveAgainstTheSceneFolder) {
    TempDir dir;
    writeFile(dir.path() / "scenes/models/tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    writeFile(dir.path() / "scenes/room.json", sceneOfObjects(R"([{"type": "mesh", "file": "models/tri.obj"}])"));
    const SceneDescription scene = loadScene(dir.path() / "scenes/room.json");
    ASSERT_EQ(scene.meshes.size(), 1u);
    EXPECT_EQ(scene.meshes[0].triangleCount(), 1u);
    EXPECT_EQ(scene.meshes[0].positions[1], glm::vec3(1, 0, 0));
    EXPECT_EQ(scene.materials.at(scene.meshes[0].faceMaterial.at(0)).name, "default");
}

TEST(SceneParser, InstancesReuseOneMesh) {
    TempDir dir;
    writeFile(dir.path() / "tri.obj", kTriangleObj);
    writeFile(dir.path() / "tri.mtl", kTriangleMtl);
    const SceneDescription scene = parseScene(R"({"meshes": {"tri": {"file": "tri.obj"}}, "objects": [
        {"type": "instance", "mesh": "tri"},
        {"type": "instance", "mesh": "tri", "transform": {"translate": [0, 0, 1]}},
        {"type": "mesh", "file": "tri.obj"}]})", dir.path() / "scene.json");
    ASSERT_EQ(scene.meshes.size(), 1u);  // the "mesh" object uses the same file, so it is loaded once too
    EXPECT_EQ(scene.instances.size(), 3u);
    EXPECT_EQ(flattenTriangles(scene).triangleCount(), 3 * scene.meshes[0].triangleCount());
}

TEST(SceneParser, MtlMaterialsAreImportedAndOverridable) {
    TempDir dir;
    writeFile(dir.path() / "tri.obj", kTriangleObj);
    writeFile(dir.path() / "tri.mtl", kTriangleMtl);
    const SceneDescription imported = parseScene(sceneOfObjects(R"([{"type": "mesh", "file": "tri.obj"}])"), dir.path() / "a.json");
    const Material* red = findMaterial(imported, "tri/red");
    ASSERT_NE(red, nullptr);
    EXPECT_EQ(red->color, glm::vec3(0.9f, 0.1f, 0.1f));
    ASSERT_NE(findMaterial(imported, "tri/blue"), nullptr);
    const TriangleMesh world = flattenTriangles(imported);
    ASSERT_EQ(world.faceMaterial.size(), 2u);
    EXPECT_EQ(imported.materials[world.faceMaterial[0]].name, "tri/red");
    EXPECT_EQ(imported.materials[world.faceMaterial[1]].name, "tri/blue");

    // A scene material with the plain name restyles the file's material.
    const SceneDescription restyled = parseScene(R"({"materials": {"red": {"type": "diffuse", "color": [0.5, 0, 0]}},
        "objects": [{"type": "mesh", "file": "tri.obj"}]})", dir.path() / "b.json");
    EXPECT_EQ(findMaterial(restyled, "tri/red"), nullptr);
    EXPECT_EQ(restyled.materials[flattenTriangles(restyled).faceMaterial[0]].color, glm::vec3(0.5f, 0, 0));

    // An object's material overrides every material of the file.
    const SceneDescription overridden = parseScene(R"({"materials": {"grey": {"type": "diffuse", "color": [0.3, 0.3, 0.3]}},
        "objects": [{"type": "mesh", "file": "tri.obj", "material": "grey"}]})", dir.path() / "c.json");
    for (uint32_t m : flattenTriangles(overridden).faceMaterial) EXPECT_EQ(overridden.materials[m].name, "grey");
}

TEST(SceneParser, ZeroAreaTrianglesAreDroppedAndCounted) {
    const SceneDescription scene = parse(sceneOfObjects(R"([{"type": "triangles",
        "vertices": [[0, 0, 0], [1, 0, 0], [0, 1, 0], [2, 0, 0]], "indices": [[0, 1, 2], [0, 1, 3]]}])"));
    ASSERT_EQ(scene.meshes.size(), 1u);
    EXPECT_EQ(scene.meshes[0].triangleCount(), 1u);
    EXPECT_EQ(scene.meshes[0].droppedDegenerate, 1u);
    EXPECT_EQ(scene.meshes[0].faceMaterial.size(), 1u);
}

// ---- errors: one test per kind

TEST(SceneParserErrors, MalformedJsonNamesLineAndColumn) {
    expectError("{\n  \"image\": {\"width\": 640,}\n}", "line 2, column 26", "malformed JSON");
}

TEST(SceneParserErrors, TruncatedJson) { expectError("{\"objects\": [", "line 1, column 14", "malformed JSON"); }

TEST(SceneParserErrors, DuplicateKey) {
    expectError(sceneWith(R"("image": {"width": 10, "width": 20})"), "image.width", "duplicate key \"width\"");
}

TEST(SceneParserErrors, UnknownKeySuggestsClosest) {
    expectError(sceneWith(R"("materials": {"red": {"type": "diffuse", "colour": [1, 0, 0]}})"), "materials.red.colour",
                "unknown key \"colour\" (did you mean \"color\"?)");
}

TEST(SceneParserErrors, UnknownKeyListsValidKeys) {
    expectError(sceneWith(R"("camera": {"zoom": 2})"), "camera.zoom", "valid keys: position, look_at, up, fov");
}

TEST(SceneParserErrors, UnknownTopLevelKey) { expectError(sceneWith(R"("light": [])"), "light", "did you mean \"lights\"?"); }

TEST(SceneParserErrors, WrongTypeForVector) {
    expectError(sceneOfObjects(R"([{"type": "sphere", "center": [0, 0], "radius": 1}])"), "objects[0].center",
                "expected an array of 3 numbers");
}

TEST(SceneParserErrors, WrongTypeForNumber) {
    expectError(sceneWith(R"("camera": {"fov": "wide"})"), "camera.fov", "expected a number, got a string");
}

TEST(SceneParserErrors, NonIntegerImageSize) { expectError(sceneWith(R"("image": {"width": 64.5})"), "image.width", "expected an integer"); }

TEST(SceneParserErrors, UnknownObjectType) {
    expectError(sceneOfObjects(R"([{"type": "pyramid"}])"), "objects[0].type", "unknown object type \"pyramid\"");
}

TEST(SceneParserErrors, UnknownLightType) {
    expectError(sceneWith(R"("lights": [{"type": "spot", "position": [0, 1, 0]}])"), "lights[0].type",
                "unknown light type \"spot\"");
}

TEST(SceneParserErrors, UnknownMaterialType) {
    expectError(sceneWith(R"("materials": {"m": {"type": "glossy"}})"), "materials.m.type", "unknown material type \"glossy\"");
}

TEST(SceneParserErrors, UnknownShape) {
    expectError(sceneOfObjects(R"([{"type": "generated", "shape": "torsu"}])"), "objects[0].shape", "did you mean \"torus\"?");
}

TEST(SceneParserErrors, UnknownMaterialName) {
    expectError(sceneOfObjects(R"([{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "whtie"}])"),
                "objects[0].material", "unknown material \"whtie\"");
}

TEST(SceneParserErrors, UnknownMeshName) {
    expectError(R"({"meshes": {"ring": {"generate": "torus"}}, "objects": [{"type": "instance", "mesh": "rings"}]})",
                "objects[0].mesh", "unknown mesh \"rings\" (did you mean \"ring\"?)");
}

TEST(SceneParserErrors, MissingRequiredKey) {
    expectError(sceneOfObjects(R"([{"type": "sphere", "center": [0, 0, 0]}])"), "objects[0]", "missing required key \"radius\"");
}

TEST(SceneParserErrors, InfiniteNumber) {
    expectError(sceneWith(R"("background": [0, 1e999, 0])"), "background[1]", "number is out of range");
    expectError(sceneWith(R"("lights": [{"type": "point", "position": [0, 1, 0], "intensity": -1e39}])"),
                "lights[0].intensity", "number is out of range");
}

TEST(SceneParserErrors, NonPositiveRadius) {
    expectError(sceneOfObjects(R"([{"type": "sphere", "center": [0, 0, 0], "radius": 0}])"), "objects[0].radius", "must be positive");
}

TEST(SceneParserErrors, FovOutOfRange) { expectError(sceneWith(R"("camera": {"fov": 180})"), "camera.fov", "must be in (0, 180)"); }

TEST(SceneParserErrors, ImageSizeOutOfRange) {
    expectError(sceneWith(R"("image": {"height": 70000})"), "image.height", "must be in 1..65536");
}

TEST(SceneParserErrors, SamplesPerPixelBelowOne) { expectError(sceneWith(R"("image": {"spp": 0})"), "image.spp", "must be in 1.."); }

TEST(SceneParserErrors, MissingMeshFileNamesTheObject) {
    TempDir dir;
    try {
        parseScene(sceneOfObjects(R"([{"type": "mesh", "file": "nowhere/missing.obj"}])"), dir.path() / "s.json");
        ADD_FAILURE() << "no error";
    } catch (const InputError& e) {
        const std::string what = e.what();
        EXPECT_EQ(e.file(), (dir.path() / "s.json").string());
        EXPECT_EQ(e.location(), "objects[0].file");
        EXPECT_NE(what.find("cannot load mesh"), std::string::npos) << what;
        EXPECT_NE(what.find("missing.obj"), std::string::npos) << what;
    }
}

TEST(SceneParserErrors, EmptyObjectList) { expectError(sceneOfObjects("[]"), "objects", "scene has no objects"); }

TEST(SceneParserErrors, NoObjectsKey) { expectError(R"({"image": {"spp": 2}})", "", "scene has no objects"); }

TEST(SceneParser, SphereWithNonUniformScaleIsAnEllipsoid) {
    const SceneDescription scene = parse(sceneOfObjects(
        R"([{"type": "sphere", "center": [1, 0, 0], "radius": 2, "transform": {"scale": [1, 3, 1]}},
            {"type": "sphere", "center": [1, 0, 0], "radius": 2, "transform": {"scale": 3}}])"));
    ASSERT_EQ(scene.analytics.size(), 1u);
    ASSERT_EQ(scene.spheres.size(), 1u);
    EXPECT_EQ(scene.analytics[0].shape, AnalyticShape::Ellipsoid);
    // The unit sphere to radius 2 at x = 1, then stretched along y: (1 +- 2, +-6, +-2).
    const glm::vec4 top = scene.analytics[0].transform * glm::vec4(0, 1, 0, 1);
    EXPECT_EQ(glm::vec3(top), glm::vec3(1, 6, 0));
    EXPECT_EQ(scene.spheres[0].center, glm::vec3(3, 0, 0));
    EXPECT_EQ(scene.spheres[0].radius, 6.0f);
}

TEST(SceneParserErrors, MatrixCombinedWithOtherKeys) {
    expectError(sceneOfObjects(R"([{"type": "generated", "shape": "cube",
        "transform": {"matrix": [1,0,0,0, 0,1,0,0, 0,0,1,0, 0,0,0,1], "scale": 2}}])"),
                "objects[0].transform", "\"matrix\" cannot be combined");
}

TEST(SceneParserErrors, ZeroScale) {
    expectError(sceneOfObjects(R"([{"type": "generated", "shape": "cube", "transform": {"scale": [1, 0, 1]}}])"),
                "objects[0].transform.scale", "must not be zero");
}

TEST(SceneParserErrors, TriangleIndexOutOfRange) {
    expectError(sceneOfObjects(R"([{"type": "triangles", "vertices": [[0, 0, 0], [1, 0, 0], [0, 1, 0]], "indices": [[0, 1, 3]]}])"),
                "objects[0].indices[0][2]", "vertex index 3 out of range (3 vertices)");
}

TEST(SceneParserErrors, OnlyZeroAreaTriangles) {
    expectError(sceneOfObjects(R"([{"type": "triangles", "vertices": [[0, 0, 0], [1, 0, 0], [2, 0, 0]], "indices": [[0, 1, 2]]}])"),
                "objects[0]", "no triangles (1 zero-area triangles dropped)");
}

TEST(SceneParserErrors, TorusTubeWiderThanRing) {
    expectError(sceneOfObjects(R"([{"type": "generated", "shape": "torus", "major_radius": 0.5, "minor_radius": 0.5}])"),
                "objects[0]", "minor_radius must be smaller than major_radius");
}

TEST(SceneParserErrors, MissingSceneFile) {
    try {
        loadScene("/nonexistent/wideray/scene.json");
        ADD_FAILURE() << "no error";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("/nonexistent/wideray/scene.json"), std::string::npos) << e.what();
    }
}

// ---- generators

/// Every edge is used once in each direction: shared by exactly two triangles, consistently wound.
void expectClosed(const TriangleMesh& mesh) {
    std::map<std::pair<uint32_t, uint32_t>, int> directedEdges;
    for (const glm::uvec3& t : mesh.triangles)
        for (int k = 0; k < 3; ++k) ++directedEdges[{t[k], t[(k + 1) % 3]}];
    for (const auto& [edge, count] : directedEdges) {
        EXPECT_EQ(count, 1) << "edge " << edge.first << "-" << edge.second;
        EXPECT_EQ(directedEdges.count({edge.second, edge.first}), 1u) << "open edge " << edge.first << "-" << edge.second;
    }
}

void expectDistinctPositions(const TriangleMesh& mesh) {
    std::set<std::tuple<float, float, float>> seen;
    for (const glm::vec3& p : mesh.positions) EXPECT_TRUE(seen.insert({p.x, p.y, p.z}).second) << p.x << " " << p.y << " " << p.z;
}

/// By the divergence theorem; positive when the triangles face outward.
double signedVolume(const TriangleMesh& mesh) {
    double volume = 0.0;
    for (const glm::uvec3& t : mesh.triangles)
        volume += glm::dot(glm::dvec3(mesh.positions[t.x]),
                           glm::cross(glm::dvec3(mesh.positions[t.y]), glm::dvec3(mesh.positions[t.z]))) / 6.0;
    return volume;
}

void expectNormalsAgreeWithWinding(const TriangleMesh& mesh) {
    ASSERT_EQ(mesh.normals.size(), mesh.positions.size());
    for (const glm::uvec3& t : mesh.triangles) {
        const glm::vec3 face = glm::cross(mesh.positions[t.y] - mesh.positions[t.x], mesh.positions[t.z] - mesh.positions[t.x]);
        for (int k = 0; k < 3; ++k) EXPECT_GT(glm::dot(face, mesh.normals[t[k]]), 0.0f);
    }
}

TEST(MeshGenerators, CubeIsClosedWithDocumentedCounts) {
    const TriangleMesh cube = makeCube();
    EXPECT_EQ(cube.positions.size(), 8u);
    EXPECT_EQ(cube.triangleCount(), 12u);
    expectClosed(cube);
    expectDistinctPositions(cube);
    EXPECT_NEAR(signedVolume(cube), 8.0, 1e-9);
    for (const glm::vec3& p : cube.positions) EXPECT_EQ(glm::abs(p), glm::vec3(1.0f));
}

TEST(MeshGenerators, IcosphereIsClosedWithDocumentedCounts) {
    for (int s = 0; s <= 3; ++s) {
        const TriangleMesh sphere = makeIcosphere(s);
        const size_t fourToS = size_t(1) << (2 * s);
        EXPECT_EQ(sphere.positions.size(), 10 * fourToS + 2);
        EXPECT_EQ(sphere.triangleCount(), 20 * fourToS);
        expectClosed(sphere);
        expectDistinctPositions(sphere);
        for (const glm::vec3& p : sphere.positions) EXPECT_NEAR(glm::length(p), 1.0f, 1e-6f);
        EXPECT_GT(signedVolume(sphere), 0.6 * 4.18879);  // a fraction of 4/3 pi, even for the icosahedron
        EXPECT_LT(signedVolume(sphere), 4.18879);
        expectNormalsAgreeWithWinding(sphere);
    }
}

TEST(MeshGenerators, TorusIsClosedWithDocumentedCounts) {
    const TriangleMesh torus = makeTorus(1.0f, 0.3f, 32, 12);
    EXPECT_EQ(torus.positions.size(), 32u * 12u);
    EXPECT_EQ(torus.triangleCount(), 2u * 32u * 12u);
    expectClosed(torus);
    expectDistinctPositions(torus);
    const double exact = 2.0 * M_PI * M_PI * 1.0 * 0.3 * 0.3;
    EXPECT_NEAR(signedVolume(torus), exact, 0.1 * exact);  // polygons lie inside the smooth torus
    expectNormalsAgreeWithWinding(torus);
}

TEST(MeshGenerators, QuadFacesUp) {
    const TriangleMesh quad = makeQuad();
    EXPECT_EQ(quad.positions.size(), 4u);
    EXPECT_EQ(quad.triangleCount(), 2u);
    expectDistinctPositions(quad);
    for (const glm::uvec3& t : quad.triangles) {
        const glm::vec3 face = glm::cross(quad.positions[t.y] - quad.positions[t.x], quad.positions[t.z] - quad.positions[t.x]);
        EXPECT_GT(face.y, 0.0f);
        EXPECT_EQ(face.x, 0.0f);
        EXPECT_EQ(face.z, 0.0f);
    }
    // The diagonal is shared; the four outer edges are the open border.
    std::map<std::pair<uint32_t, uint32_t>, int> edges;
    for (const glm::uvec3& t : quad.triangles)
        for (int k = 0; k < 3; ++k) ++edges[std::minmax(t[k], t[(k + 1) % 3])];
    EXPECT_EQ(edges.size(), 5u);
    for (const glm::vec3& p : quad.positions) {
        EXPECT_EQ(p.y, 0.0f);
        EXPECT_EQ(glm::abs(glm::vec2(p.x, p.z)), glm::vec2(1.0f));
    }
}

} // namespace
} // namespace wideray
