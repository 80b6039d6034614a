// Mesh loading: OBJ, PLY (all three encodings) and glTF from small files written here, plus the
// shared real-world scenes when they are available.
#include <bit>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>
#include <unistd.h>

#include <gtest/gtest.h>

#include "core/error.h"
#include "io/image_io.h"
#include "io/mesh_framing.h"
#include "io/mesh_io.h"
#include "render_helpers.h"
#include "test_data.h"

namespace wideray {
namespace {

class MeshIoTest : public ::testing::Test {
protected:
    void SetUp() override {
        const std::string testName = ::testing::UnitTest::GetInstance()->current_test_info()->name();
        dir_ = std::filesystem::temp_directory_path() /
               ("wideray_mesh_io_" + std::to_string(getpid()) + "_" + testName);
        std::filesystem::create_directories(dir_);
    }
    void TearDown() override { std::filesystem::remove_all(dir_); }

    std::filesystem::path write(const std::string& name, const std::string& content) const {
        const std::filesystem::path path = dir_ / name;
        std::ofstream(path, std::ios::binary) << content;
        return path;
    }

    std::filesystem::path dir_;
};

/// Expects `load` to throw an InputError whose message contains every one of `fragments`.
template <class Load>
void expectInputError(Load load, std::initializer_list<std::string> fragments) {
    try {
        load();
        ADD_FAILURE() << "no InputError thrown";
    } catch (const InputError& error) {
        for (const std::string& fragment : fragments)
            EXPECT_NE(std::string(error.what()).find(fragment), std::string::npos)
                << "'" << error.what() << "' lacks '" << fragment << "'";
    }
}

// ---- PLY writing -------------------------------------------------------------------------------

/// One value of a PLY body with its header type name.
struct PlyValue {
    std::string type;
    double value;
};
using PlyItem = std::vector<PlyValue>; // one element item (one line in ascii)

template <class T>
void appendBinary(std::string& bytes, T value, bool bigEndian) {
    char raw[sizeof(T)];
    std::memcpy(raw, &value, sizeof(T));
    if (bigEndian) std::reverse(raw, raw + sizeof(T));
    bytes.append(raw, sizeof(T));
}

/// A PLY file in `format` ("ascii", "binary_little_endian", "binary_big_endian").
std::string plyFile(const std::string& format, const std::string& elements, const std::vector<PlyItem>& items) {
    std::string text = "ply\nformat " + format + " 1.0\ncomment written by test_mesh_io\n" + elements + "end_header\n";
    const bool bigEndian = format == "binary_big_endian";
    for (const PlyItem& item : items) {
        for (const PlyValue& v : item) {
            if (format == "ascii") {
                char number[32];
                std::snprintf(number, sizeof number, "%.9g ", v.value);
                text += number;
            } else if (v.type == "uchar") appendBinary(text, uint8_t(v.value), bigEndian);
            else if (v.type == "short") appendBinary(text, int16_t(v.value), bigEndian);
            else if (v.type == "int") appendBinary(text, int32_t(v.value), bigEndian);
            else if (v.type == "uint") appendBinary(text, uint32_t(v.value), bigEndian);
            else if (v.type == "float") appendBinary(text, float(v.value), bigEndian);
            else if (v.type == "double") appendBinary(text, v.value, bigEndian);
            else ADD_FAILURE() << "test writes no type " << v.type;
        }
        if (format == "ascii") text += "\n";
    }
    return text;
}

const std::string cubeElements = "element vertex 8\nproperty float x\nproperty double y\nproperty float z\n"
                                 "element face 6\nproperty list uchar int vertex_indices\n";

std::vector<PlyItem> cubeItems() {
    std::vector<PlyItem> items;
    for (int i = 0; i < 8; ++i)
        items.push_back({{"float", double(i & 1)}, {"double", double((i >> 1) & 1)}, {"float", double(i >> 2)}});
    const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
    for (const auto& quad : quads)
        items.push_back({{"uchar", 4}, {"int", double(quad[0])}, {"int", double(quad[1])}, {"int", double(quad[2])},
                         {"int", double(quad[3])}});
    return items;
}

const char* const plyFormats[] = {"ascii", "binary_little_endian", "binary_big_endian"};

// ---- PLY ---------------------------------------------------------------------------------------

TEST_F(MeshIoTest, PlyCubeIsTheSameInAllEncodings) {
    std::vector<TriangleMesh> meshes;
    for (const char* format : plyFormats)
        meshes.push_back(loadMesh(write(std::string(format) + ".ply", plyFile(format, cubeElements, cubeItems()))));

    const TriangleMesh& ascii = meshes[0];
    ASSERT_EQ(ascii.positions.size(), 8u);
    ASSERT_EQ(ascii.triangleCount(), 12u);
    EXPECT_EQ(ascii.positions[5], glm::vec3(1, 0, 1));
    EXPECT_EQ(ascii.triangles[0], glm::uvec3(0, 2, 3)); // fan from the first corner
    EXPECT_EQ(ascii.triangles[1], glm::uvec3(0, 3, 1));
    EXPECT_TRUE(ascii.normals.empty());
    EXPECT_TRUE(ascii.faceMaterial.empty());
    EXPECT_EQ(ascii.droppedDegenerate, 0u);
    for (size_t m = 1; m < meshes.size(); ++m) {
        EXPECT_EQ(meshes[m].positions, ascii.positions) << plyFormats[m];
        EXPECT_EQ(meshes[m].triangles, ascii.triangles) << plyFormats[m];
    }
}

TEST_F(MeshIoTest, PlySkipsExtraPropertiesAndElements) {
    const std::string elements = "element vertex 4\n"
                                 "property float x\nproperty float y\nproperty float z\n"
                                 "property float confidence\nproperty list uchar short neighbours\n"
                                 "property float nx\nproperty float ny\nproperty float nz\n"
                                 "property float s\nproperty float t\n"
                                 "element edge 2\nproperty int vertex1\nproperty int vertex2\n"
                                 "element face 2\nproperty uchar intensity\n"
                                 "property list uchar uint vertex_index\n"
                                 "property list int float texcoord\nproperty int flags\n"
                                 "element material 1\nproperty list uchar uchar name\n";
    std::vector<PlyItem> items;
    for (int i = 0; i < 4; ++i)
        items.push_back({{"float", double(i & 1)}, {"float", double(i >> 1)}, {"float", 0}, {"float", 0.5},
                         {"uchar", 2}, {"short", 7}, {"short", -7}, {"float", 0}, {"float", 0}, {"float", 1},
                         {"float", 0.25 * i}, {"float", 1 - 0.25 * i}});
    items.push_back({{"int", 0}, {"int", 1}});
    items.push_back({{"int", 1}, {"int", 3}});
    items.push_back({{"uchar", 200}, {"uchar", 3}, {"uint", 0}, {"uint", 1}, {"uint", 3}, {"int", 2}, {"float", 0.5},
                     {"float", 0.5}, {"int", -1}});
    items.push_back({{"uchar", 100}, {"uchar", 3}, {"uint", 0}, {"uint", 3}, {"uint", 2}, {"int", 0}, {"int", 9}});
    items.push_back({{"uchar", 3}, {"uchar", 'a'}, {"uchar", 'b'}, {"uchar", 'c'}});

    for (const char* format : plyFormats) {
        SCOPED_TRACE(format);
        const TriangleMesh mesh = loadPly(write(std::string(format) + ".ply", plyFile(format, elements, items)));
        ASSERT_EQ(mesh.positions.size(), 4u);
        EXPECT_EQ(mesh.positions[3], glm::vec3(1, 1, 0));
        ASSERT_EQ(mesh.normals.size(), 4u);
        EXPECT_EQ(mesh.normals[2], glm::vec3(0, 0, 1));
        ASSERT_EQ(mesh.uvs.size(), 4u);
        EXPECT_EQ(mesh.uvs[1], glm::vec2(0.25f, 0.75f));
        ASSERT_EQ(mesh.triangleCount(), 2u);
        EXPECT_EQ(mesh.triangles[0], glm::uvec3(0, 1, 3));
        EXPECT_EQ(mesh.triangles[1], glm::uvec3(0, 3, 2));
    }
}

TEST_F(MeshIoTest, TruncatedBinaryPlyNamesTheElementAndItem) {
    const std::string whole = plyFile("binary_little_endian", cubeElements, cubeItems());
    const auto inFaces = write("in_faces.ply", whole.substr(0, whole.size() - 10));
    expectInputError([&] { loadMesh(inFaces); }, {"in_faces.ply", "file ends in face 5 of 6"});

    const size_t bodyStart = whole.find("end_header\n") + 11;
    const size_t vertexBytes = 4 + 8 + 4;
    const auto inVertices = write("in_vertices.ply", whole.substr(0, bodyStart + 3 * vertexBytes + 5));
    expectInputError([&] { loadMesh(inVertices); }, {"in_vertices.ply", "file ends in vertex 3 of 8"});
}

TEST_F(MeshIoTest, TruncatedAsciiPlyNamesTheLine) {
    const std::string whole = plyFile("ascii", cubeElements, cubeItems());
    const auto path = write("short.ply", whole.substr(0, whole.find("4 0 4 6 2")));
    expectInputError([&] { loadMesh(path); }, {"short.ply:line 23", "file ends in face 4 of 6"});
}

TEST_F(MeshIoTest, PlyHeaderErrors) {
    const auto notPly = write("not.ply", "solid cube\n");
    expectInputError([&] { loadPly(notPly); }, {"not.ply:line 1", "not a PLY file"});
    const auto badFormat = write("format.ply", "ply\nformat binary_middle_endian 1.0\nend_header\n");
    expectInputError([&] { loadPly(badFormat); }, {"line 2", "unknown format 'binary_middle_endian'"});
    const auto badType = write("type.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty half x\nend_header\n");
    expectInputError([&] { loadPly(badType); }, {"line 4", "unsupported property type 'half'"});
    // Found by ply_fuzzer: a float count of 4.7e30 items reached an out-of-range float-to-integer cast.
    const auto floatCount = write("count.ply", "ply\nformat ascii 1.0\nelement edge 1\nproperty list float int e\n"
                                               "end_header\n4.7e30 1 2\n");
    expectInputError([&] { loadPly(floatCount); }, {"line 4", "a list's count type must be an integer type"});
}

TEST_F(MeshIoTest, PlyFaceWithTwoVerticesIsAnError) {
    const auto path = write("two.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                                       "property float z\nelement face 1\nproperty list uchar int vertex_indices\n"
                                       "end_header\n0 0 0\n1 0 0\n0 1 0\n2 0 1\n");
    expectInputError([&] { loadPly(path); }, {"two.ply:line 13", "face 0 has 2 vertices"});
}

TEST_F(MeshIoTest, PlyIndexOutOfRangeIsAnError) {
    std::vector<PlyItem> items = cubeItems();
    items[8 + 2][3].value = 8;
    for (const char* format : {"ascii", "binary_big_endian"}) {
        const auto path = write(std::string(format) + ".ply", plyFile(format, cubeElements, items));
        expectInputError([&] { loadPly(path); }, {format, "face 2 refers to vertex 8"});
    }
}

TEST_F(MeshIoTest, NanCoordinateIsAnError) {
    const auto path = write("nan.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                                       "property float z\nelement face 1\nproperty list uchar int vertex_indices\n"
                                       "end_header\n0 0 0\n1 nan 0\n0 1 0\n3 0 1 2\n");
    expectInputError([&] { loadPly(path); }, {"nan.ply:vertex 1", "NaN or infinite"});
}

// ---- validateMesh ------------------------------------------------------------------------------

TEST_F(MeshIoTest, PlyElementWithoutPropertiesIsSkippedAtOnce) {
    // Found by ply_fuzzer: such an element with a count of 2^62 was counted through item by item.
    for (const char* format : plyFormats) {
        const std::string ply = plyFile(format, "element marker 4611686018427387904\n" + cubeElements, cubeItems());
        EXPECT_EQ(parsePly(ply, "marker.ply").triangleCount(), 12u) << format;
    }
}

// Inputs the fuzzers found (fuzz/, docs/robustness.md), kept as they were found: each ends in a mesh or
// an InputError, at once.
TEST(FuzzRegressions, EndInAMeshOrAnInputError) {
    const std::filesystem::path folder = std::filesystem::path(WIDERAY_SOURCE_DIR) / "tests/data/fuzz";
    size_t inputs = 0;
    for (const auto& entry : std::filesystem::directory_iterator(folder)) {
        std::ifstream in(entry.path(), std::ios::binary);
        const std::string data((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
        const std::string ext = entry.path().extension().string(), name = entry.path().string();
        try {
            if (ext == ".ply") parsePly(data, name);
            else if (ext == ".obj") {  // as obj_fuzzer reads it: OBJ text, NUL, MTL text
                const size_t split = data.find('\0');
                parseObj(data.substr(0, split), split == std::string::npos ? "" : data.substr(split + 1), name);
            }
            else if (ext == ".gltf" || ext == ".glb") parseGltf(data, name);
            else ADD_FAILURE() << "no reader for " << name;
        } catch (const InputError& e) {
            EXPECT_NE(std::string(e.what()).find(name), std::string::npos) << e.what();
        }
        ++inputs;
    }
    EXPECT_GT(inputs, 0u);
}

TEST(ValidateMesh, DropsZeroAreaTrianglesKeepingMaterialsInStep) {
    TriangleMesh mesh;
    mesh.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {2, 0, 0}};
    mesh.triangles = {{0, 1, 2}, {0, 1, 3}, {1, 1, 2}, {2, 1, 0}};
    mesh.faceMaterial = {7, 8, 9, 10};
    validateMesh(mesh, "m.ply");
    EXPECT_EQ(mesh.triangles, (std::vector<glm::uvec3>{{0, 1, 2}, {2, 1, 0}}));
    EXPECT_EQ(mesh.faceMaterial, (std::vector<uint32_t>{7, 10}));
    EXPECT_EQ(mesh.droppedDegenerate, 2u);
}

TEST(ValidateMesh, OutOfRangeIndexNamesTheTriangle) {
    TriangleMesh mesh;
    mesh.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    mesh.triangles = {{0, 1, 2}, {0, 3, 2}};
    expectInputError([&] { validateMesh(mesh, "m.obj"); }, {"m.obj:triangle 1", "vertex index 3 out of range"});
}

TEST(ValidateMesh, InfiniteCoordinateNamesTheVertex) {
    TriangleMesh mesh;
    mesh.positions = {{0, 0, 0}, {1, 0, 0}, {0, INFINITY, 0}};
    mesh.triangles = {{0, 1, 2}};
    expectInputError([&] { validateMesh(mesh, "m.obj"); }, {"m.obj:vertex 2"});
}

TEST(ValidateMesh, OnlyDegenerateTrianglesLeaveNoTriangles) {
    TriangleMesh mesh;
    mesh.positions = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}};
    mesh.triangles = {{0, 1, 2}};
    expectInputError([&] { validateMesh(mesh, "m.obj"); }, {"no triangles"});
}

TEST_F(MeshIoTest, ZeroAreaTriangleInFileIsDroppedAndCounted) {
    const auto path = write("flat.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 2 0 0\nf 1 2 3\nf 1 2 4\n");
    const TriangleMesh mesh = loadMesh(path);
    EXPECT_EQ(mesh.triangleCount(), 1u);
    EXPECT_EQ(mesh.droppedDegenerate, 1u);
}

// ---- OBJ ---------------------------------------------------------------------------------------

TEST_F(MeshIoTest, ObjQuadWithMaterials) {
    write("quad.mtl", "newmtl red\nKd 1 0 0\n\nnewmtl blue\nKd 0 0 0.5\n");
    const auto path = write("Quad.OBJ", "mtllib quad.mtl\n"
                                        "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\n"
                                        "f 1 2 5\n"
                                        "usemtl blue\nf 1 2 3 4\n");
    const TriangleMesh mesh = loadMesh(path);
    ASSERT_EQ(mesh.triangleCount(), 3u);
    EXPECT_EQ(mesh.positions.size(), 5u);
    EXPECT_EQ(mesh.triangles[1], glm::uvec3(0, 1, 2));
    EXPECT_EQ(mesh.triangles[2], glm::uvec3(0, 2, 3));
    ASSERT_EQ(mesh.faceMaterial.size(), 3u);
    EXPECT_EQ(mesh.materials[mesh.faceMaterial[0]].name, "default");
    EXPECT_EQ(mesh.materials[mesh.faceMaterial[1]].name, "blue");
    EXPECT_EQ(mesh.materials[mesh.faceMaterial[1]].diffuse, glm::vec3(0, 0, 0.5f));
    EXPECT_EQ(mesh.faceMaterial[2], mesh.faceMaterial[1]);
    EXPECT_EQ(mesh.materials[0].name, "red");
    EXPECT_EQ(mesh.materials[0].diffuse, glm::vec3(1, 0, 0));
}

TEST_F(MeshIoTest, ObjCornersWithDifferentNormalsBecomeSeparateVertices) {
    const auto path = write("normals.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvn 0 0 1\nvn 0 0 -1\n"
                                           "vt 0 0\nvt 1 1\n"
                                           "f 1/1/1 2/1/1 3/2/1\nf 1/1/2 3/2/2 4/2/2\n");
    const TriangleMesh mesh = loadObj(path);
    ASSERT_EQ(mesh.positions.size(), 6u);
    ASSERT_EQ(mesh.normals.size(), 6u);
    ASSERT_EQ(mesh.uvs.size(), 6u);
    EXPECT_TRUE(mesh.faceMaterial.empty());
    const glm::uvec3 second = mesh.triangles[1];
    EXPECT_EQ(mesh.positions[second.x], glm::vec3(0, 0, 0));
    EXPECT_EQ(mesh.normals[second.x], glm::vec3(0, 0, -1));
    EXPECT_EQ(mesh.normals[mesh.triangles[0].x], glm::vec3(0, 0, 1));
    EXPECT_EQ(mesh.uvs[second.y], glm::vec2(1, 1));
}

TEST_F(MeshIoTest, ObjNormalsOnSomeFacesOnlyAreDropped) {
    const auto path = write("some.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvn 0 0 1\n"
                                        "f 1//1 2//1 3//1\nf 1 3 4\n");
    const TriangleMesh mesh = loadObj(path);
    EXPECT_EQ(mesh.positions.size(), 4u);
    EXPECT_TRUE(mesh.normals.empty());
    EXPECT_EQ(mesh.triangleCount(), 2u);
}

TEST_F(MeshIoTest, ObjIndexOutOfRangeIsAnError) {
    const auto past = write("past.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n");
    expectInputError([&] { loadObj(past); }, {"past.obj", "face 0", "vertex index 9 out of range"});
    const auto before = write("before.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 -7\n");
    expectInputError([&] { loadObj(before); }, {"before.obj", "out of range"});
    const auto quad = write("quad.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3 4\n");
    expectInputError([&] { loadObj(quad); }, {"quad.obj", "vertex index 4 out of range"});
}

TEST_F(MeshIoTest, ObjMissingMtlIsOnlyAWarning) {
    const auto path = write("nomtl.obj", "mtllib absent.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl red\nf 1 2 3\n");
    ::testing::internal::CaptureStderr();
    const TriangleMesh mesh = loadObj(path);
    const std::string warnings = ::testing::internal::GetCapturedStderr();
    EXPECT_EQ(mesh.triangleCount(), 1u);
    EXPECT_NE(warnings.find("absent.mtl"), std::string::npos) << warnings;
}

// ---- dispatch and missing files ----------------------------------------------------------------

TEST_F(MeshIoTest, UnknownExtensionIsAnError) {
    const auto path = write("mesh.stl", "solid\n");
    expectInputError([&] { loadMesh(path); }, {"mesh.stl", "'.stl'", ".obj, .ply, .gltf, .glb"});
}

TEST_F(MeshIoTest, MissingFileIsAnError) {
    for (const char* name : {"absent.obj", "absent.ply", "absent.gltf", "absent.glb"})
        expectInputError([&] { loadMesh(dir_ / name); }, {name, "cannot open file"});
}

// ---- glTF --------------------------------------------------------------------------------------

std::string base64(const std::string& bytes) {
    static const char digits[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string text;
    for (size_t i = 0; i < bytes.size(); i += 3) {
        uint32_t group = uint32_t(uint8_t(bytes[i])) << 16;
        if (i + 1 < bytes.size()) group |= uint32_t(uint8_t(bytes[i + 1])) << 8;
        if (i + 2 < bytes.size()) group |= uint8_t(bytes[i + 2]);
        for (size_t k = 0; k < 4; ++k) text += i + k <= bytes.size() ? digits[(group >> (18 - 6 * k)) & 63] : '=';
    }
    return text;
}

/// One triangle's positions then its uint16 indices: 42 bytes.
std::string triangleBuffer() {
    std::string buffer;
    for (float value : {0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 0.f, 1.f, 0.f}) appendBinary(buffer, value, false);
    for (uint16_t index : {0, 1, 2}) appendBinary(buffer, index, false);
    return buffer;
}

/// glTF JSON for triangleBuffer() under a translated parent node and a scaled child node; the
/// buffer is embedded as a data URI unless `bufferUri` is false (as in a .glb); `extra` adds
/// top-level members.
std::string triangleGltf(const std::string& extra, bool bufferUri = true) {
    const std::string uri = bufferUri ? R"(, "uri": "data:application/octet-stream;base64,)" + base64(triangleBuffer()) + "\"" : "";
    return R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}],
  "nodes": [{"translation": [1, 2, 3], "children": [1]}, {"scale": [2, 2, 2], "mesh": 0}],
  "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1, "material": 0}]}],
  "accessors": [
    {"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0,0,0], "max": [1,1,0]},
    {"bufferView": 1, "componentType": 5123, "count": 3, "type": "SCALAR"}],
  "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 36}, {"buffer": 0, "byteOffset": 36, "byteLength": 6}],
  "buffers": [{"byteLength": 42)" + uri + "}]" + extra + "}";
}

/// A binary glTF: header, JSON chunk and BIN chunk, each chunk padded to 4 bytes.
std::string glbFile(std::string json, std::string bin) {
    json.resize((json.size() + 3) / 4 * 4, ' ');
    bin.resize((bin.size() + 3) / 4 * 4, '\0');
    std::string file = "glTF";
    appendBinary(file, uint32_t(2), false);
    appendBinary(file, uint32_t(12 + 8 + json.size() + 8 + bin.size()), false);
    appendBinary(file, uint32_t(json.size()), false);
    file += "JSON" + json;
    appendBinary(file, uint32_t(bin.size()), false);
    file += std::string("BIN\0", 4) + bin;
    return file;
}

TEST_F(MeshIoTest, GltfNodeTransformsApply) {
    const auto path = write("triangle.gltf", triangleGltf(R"(, "materials": [{"name": "paint",
        "pbrMetallicRoughness": {"baseColorFactor": [0.25, 0.5, 0.75, 1]}}])"));
    const TriangleMesh mesh = loadMesh(path);
    ASSERT_EQ(mesh.positions.size(), 3u);
    EXPECT_EQ(mesh.positions[0], glm::vec3(1, 2, 3));
    EXPECT_EQ(mesh.positions[1], glm::vec3(3, 2, 3));
    EXPECT_EQ(mesh.positions[2], glm::vec3(1, 4, 3));
    ASSERT_EQ(mesh.triangleCount(), 1u);
    EXPECT_EQ(mesh.triangles[0], glm::uvec3(0, 1, 2));
    ASSERT_EQ(mesh.faceMaterial, std::vector<uint32_t>{0});
    EXPECT_EQ(mesh.materials[0].name, "paint");
    EXPECT_EQ(mesh.materials[0].diffuse, glm::vec3(0.25f, 0.5f, 0.75f));
}

TEST_F(MeshIoTest, GlbLoadsLikeGltf) {
    const auto path = write("triangle.GLB", glbFile(triangleGltf("", false), triangleBuffer()));
    const TriangleMesh mesh = loadMesh(path);
    ASSERT_EQ(mesh.positions.size(), 3u);
    EXPECT_EQ(mesh.positions[2], glm::vec3(1, 4, 3));
    EXPECT_EQ(mesh.triangleCount(), 1u);
    EXPECT_TRUE(mesh.faceMaterial.empty()); // the file has no materials, although the primitive names one
}

void expectSameMesh(const TriangleMesh& a, const TriangleMesh& b) {
    EXPECT_EQ(a.positions, b.positions);
    EXPECT_EQ(a.triangles, b.triangles);
    EXPECT_EQ(a.faceMaterial, b.faceMaterial);
    ASSERT_EQ(a.materials.size(), b.materials.size());
    for (size_t m = 0; m < a.materials.size(); ++m) {
        EXPECT_EQ(a.materials[m].name, b.materials[m].name);
        EXPECT_EQ(a.materials[m].diffuse, b.materials[m].diffuse);
    }
}

// The in-memory entry points (the fuzzing harnesses', fuzz/) read what the file loaders read.
TEST_F(MeshIoTest, MeshesFromMemoryEqualMeshesFromFiles) {
    const std::string mtl = "newmtl red\nKd 1 0 0\nnewmtl blue\nKd 0 0 0.5\n";
    const std::string obj = "mtllib quad.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nf 1 2 5\n"
                            "usemtl blue\nf 1 2 3 4\n";
    write("quad.mtl", mtl);
    expectSameMesh(parseObj(obj, mtl, "quad.obj"), loadMesh(write("quad.obj", obj)));
    for (const char* format : plyFormats) {
        const std::string ply = plyFile(format, cubeElements, cubeItems());
        expectSameMesh(parsePly(ply, "cube.ply"), loadMesh(write("cube.ply", ply)));
    }
    const std::string gltf = triangleGltf(R"(, "materials": [{"name": "paint",
        "pbrMetallicRoughness": {"baseColorFactor": [0.25, 0.5, 0.75, 1]}}])");
    expectSameMesh(parseGltf(gltf, dir_ / "triangle.gltf"), loadMesh(write("triangle.gltf", gltf)));
    const std::string glb = glbFile(triangleGltf("", false), triangleBuffer());
    expectSameMesh(parseGltf(glb, dir_ / "triangle.glb"), loadMesh(write("triangle.glb", glb)));
    expectInputError([] { parsePly("ply\nformat ascii 1.0\nelement vertex 3\nend_header\n1 2", "m.ply"); }, {"m.ply"});
    expectInputError([] { parseGltf("{", "m.gltf"); }, {"m.gltf"});
    expectInputError([] { parseObj("f 1 2 3\n", "", "m.obj"); }, {"m.obj"});
}

TEST_F(MeshIoTest, GltfAllocatesNoMoreThanItsDataJustifies) {
    // Found by gltf_fuzzer: an accessor without bufferView (all zeros) of count 215,122,229 took 2.6 GB.
    const std::string zeros = R"({"asset": {"version": "2.0"}, "nodes": [{"mesh": 0}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
        "accessors": [{"componentType": 5126, "count": 215122229, "type": "VEC3"}]})";
    expectInputError([&] { parseGltf(zeros, "zeros.gltf"); }, {"zeros.gltf:accessors[0]", "count 215122229", "justify"});
    // A node under two parents would repeat its subtree once per path: 2^30 copies from 30 such nodes.
    std::string nodes;
    for (int i = 0; i < 30; ++i) nodes += R"({"children": [)" + std::to_string(i + 1) + "," + std::to_string(i + 1) + "]},";
    const std::string dag = R"({"asset": {"version": "2.0"}, "nodes": [)" + nodes +
                            R"({}]})";
    expectInputError([&] { parseGltf(dag, "dag.gltf"); }, {"dag.gltf:nodes[30]", "reached twice"});
}

TEST_F(MeshIoTest, GltfWithMissingTextureLoadsWithAWarning) {
    const auto path = write("textured.gltf", triangleGltf(R"(,
        "materials": [{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}],
        "textures": [{"source": 0}], "images": [{"uri": "missing_albedo.png"}])"));
    ::testing::internal::CaptureStderr();
    const TriangleMesh mesh = loadGltf(path);
    const std::string warnings = ::testing::internal::GetCapturedStderr();
    EXPECT_EQ(mesh.triangleCount(), 1u);
    EXPECT_EQ(mesh.materials.at(0).diffuse, glm::vec3(1));
    EXPECT_NE(warnings.find("missing_albedo.png"), std::string::npos) << warnings;
}

TEST_F(MeshIoTest, GltfParseErrorIsAnInputError) {
    const auto path = write("broken.gltf", "{\"asset\": ");
    expectInputError([&] { loadGltf(path); }, {"broken.gltf"});
}

// ---- shared real-world scenes ------------------------------------------------------------------

TriangleMesh loadSharedScene(const std::string& relativePath) {
    const std::optional<std::filesystem::path> scenes = sharedScenesDir();
    if (!scenes) return {};
    return loadMesh(*scenes / relativePath);
}

#define SKIP_WITHOUT_SHARED_SCENES() \
    if (!sharedScenesDir()) GTEST_SKIP() << "no shared scenes directory (set WIDERAY_SCENES)"

TEST(SharedScenes, StanfordBunnyAsciiPly) {
    SKIP_WITHOUT_SHARED_SCENES();
    const TriangleMesh mesh = loadSharedScene("stanford-bunny/bun_zipper.ply");
    EXPECT_EQ(mesh.positions.size(), 35947u);
    EXPECT_EQ(mesh.triangleCount() + mesh.droppedDegenerate, 69451u);
    EXPECT_LT(mesh.droppedDegenerate, 10u);
}

TEST(SharedScenes, StanfordDragonBinaryPly) {
    SKIP_WITHOUT_SHARED_SCENES();
    const TriangleMesh mesh = loadSharedScene("stanford-dragon-100k/dragon_100k.ply");
    EXPECT_EQ(mesh.positions.size(), 50000u);
    EXPECT_EQ(mesh.normals.size(), 50000u);
    EXPECT_EQ(mesh.triangleCount() + mesh.droppedDegenerate, 100000u);
}

TEST(SharedScenes, CornellBoxObjWithMaterials) {
    SKIP_WITHOUT_SHARED_SCENES();
    const TriangleMesh mesh = loadSharedScene("cornell-box/CornellBox-Original.obj");
    EXPECT_EQ(mesh.triangleCount() + mesh.droppedDegenerate, 36u);
    EXPECT_GE(mesh.materials.size(), 3u);
    EXPECT_EQ(mesh.faceMaterial.size(), mesh.triangleCount());
}

TEST(SharedScenes, TeapotObj) {
    SKIP_WITHOUT_SHARED_SCENES();
    const TriangleMesh mesh = loadSharedScene("teapot/teapot.obj");
    EXPECT_EQ(mesh.triangleCount() + mesh.droppedDegenerate, 6320u);
}

// ---- bare meshes shown as their authors meant (io/mesh_framing.h, showcaseMesh) -----------------

/// The mean color of the pixels that show the model (not the background).
glm::vec3 modelColor(const SceneDescription& scene) {
    RenderOptions options;
    const Image image = renderWithReference(scene, 1, options);
    glm::dvec3 sum(0.0);
    size_t n = 0;
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x) {
            const glm::vec3 c(image.at(x, y)[0], image.at(x, y)[1], image.at(x, y)[2]);
            if (glm::length(c - scene.background) < 1e-4f) continue;
            sum += glm::dvec3(c);
            ++n;
        }
    EXPECT_GT(n, size_t(image.width * image.height / 20)) << "the model covers little of the image";
    return n ? glm::vec3(sum / double(n)) : glm::vec3(0.0f);
}

/// Every vertex of the mesh lies inside the camera's frustum.
void expectWholeMeshInView(const SceneDescription& scene) {
    const Camera& camera = scene.camera;
    const glm::vec3 forward = glm::normalize(camera.lookAt - camera.position);
    const glm::vec3 right = glm::normalize(glm::cross(forward, camera.up)), up = glm::cross(right, forward);
    const float tanY = std::tan(glm::radians(camera.fovY) * 0.5f);
    const float tanX = tanY * float(scene.image.width) / float(scene.image.height);
    for (const glm::vec3& v : scene.meshes[0].positions) {
        const glm::vec3 d = v - camera.position;
        const float z = glm::dot(d, forward);
        ASSERT_GT(z, 0.0f);
        ASSERT_LE(std::abs(glm::dot(d, right)), z * tanX) << scene.image.width << "x" << scene.image.height;
        ASSERT_LE(std::abs(glm::dot(d, up)), z * tanY) << scene.image.width << "x" << scene.image.height;
    }
}

TEST_F(MeshIoTest, ShowcaseFramesTheWholeMesh) {
    // A long thin box, in images wide and tall: the narrower side decides.
    TriangleMesh rod;
    for (int i = 0; i < 8; ++i) rod.positions.emplace_back(i & 1 ? 10.0f : -10.0f, i & 2 ? 1.0f : -1.0f, i & 4 ? 0.5f : -0.5f);
    rod.triangles = {{0, 1, 3}, {0, 3, 2}, {4, 6, 7}, {4, 7, 5}, {0, 4, 5}, {0, 5, 1}, {2, 3, 7}, {2, 7, 6}};
    for (auto [w, h] : {std::pair{200, 100}, {100, 200}, {64, 64}}) expectWholeMeshInView(showcaseMesh(rod, "rod.obj", w, h));
    if (const auto shared = sharedScenesDir()) {
        const SceneDescription bunny = loadSceneOrMesh(*shared / "stanford-bunny/bun_zipper.ply", 160, 90, MeshFraming::Showcase);
        expectWholeMeshInView(bunny);
        EXPECT_EQ(bunny.lights.size(), 2u);  // the key light and the fill light at the camera
    }
}

/// A cube of side 2 about the origin with texture coordinates on each face, in OBJ, using `material`.
std::string cubeObj(const std::string& mtllib, const std::string& material) {
    std::string obj = mtllib.empty() ? "" : "mtllib " + mtllib + "\n";
    for (int i = 0; i < 8; ++i)
        obj += std::string("v ") + (i & 1 ? "1" : "-1") + (i & 2 ? " 1" : " -1") + (i & 4 ? " 1" : " -1") + "\n";
    obj += "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n";
    if (!material.empty()) obj += "usemtl " + material + "\n";
    for (const char* face : {"1/1 3/2 4/3 2/4", "5/1 6/2 8/3 7/4", "1/1 2/2 6/3 5/4", "3/1 7/2 8/3 4/4", "1/1 5/2 7/3 3/4", "2/1 4/2 8/3 6/4"})
        obj += std::string("f ") + face + "\n";
    return obj;
}

TEST_F(MeshIoTest, ShowcaseKeepsTheFilesMaterials) {
    // MTL Kd: a red cube.
    write("red.mtl", "newmtl red\nKd 0.9 0.05 0.05\n");
    const glm::vec3 red = modelColor(loadSceneOrMesh(write("red.obj", cubeObj("red.mtl", "red")), 48, 48, MeshFraming::Showcase));
    EXPECT_GT(red.r, 4 * red.g);
    EXPECT_GT(red.r, 4 * red.b);
    // Without materials: grey, and lit everywhere (no black faces).
    const glm::vec3 grey = modelColor(loadSceneOrMesh(write("plain.obj", cubeObj("", "")), 48, 48, MeshFraming::Showcase));
    EXPECT_NEAR(grey.r, grey.b, 1e-3f);
    EXPECT_GT(grey.r, 0.05f);
    // MTL map_Kd: a blue image over the cube's faces.
    Image blue(2, 2, 3);
    for (size_t i = 0; i < blue.pixels.size(); i += 3) blue.pixels[i + 2] = 1.0f;
    writeImage(blue, dir_ / "blue.png", true);
    write("textured.mtl", "newmtl painted\nKd 0.8 0.8 0.8\nmap_Kd blue.png\n");
    const glm::vec3 painted = modelColor(loadSceneOrMesh(write("textured.obj", cubeObj("textured.mtl", "painted")), 48, 48, MeshFraming::Showcase));
    EXPECT_GT(painted.b, 4 * painted.r);
    // A missing image is reported, and the Kd color is used.
    write("missing.mtl", "newmtl gone\nKd 0.1 0.8 0.1\nmap_Kd nowhere.png\n");
    const SceneDescription missing = loadSceneOrMesh(write("missing.obj", cubeObj("missing.mtl", "gone")), 48, 48, MeshFraming::Showcase);
    ASSERT_EQ(missing.warnings.size(), 1u);
    EXPECT_NE(missing.warnings[0].find("nowhere.png"), std::string::npos) << missing.warnings[0];
    const glm::vec3 green = modelColor(missing);
    EXPECT_GT(green.g, 4 * green.r);
    // glTF baseColorFactor.
    const glm::vec3 gltf = modelColor(loadSceneOrMesh(
        write("tri.gltf", triangleGltf(R"(, "materials": [{"pbrMetallicRoughness": {"baseColorFactor": [0.05, 0.1, 0.9, 1]}}])")), 48,
        48, MeshFraming::Showcase));
    EXPECT_GT(gltf.b, 4 * gltf.r);
}

/// A PLY square of two triangles facing +z whose vertices carry `colors` (properties of `type`).
std::string coloredSquarePly(const std::string& type, const std::string& colors) {
    return "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
           "property " + type + " red\nproperty " + type + " green\nproperty " + type + " blue\n"
           "element face 2\nproperty list uchar int vertex_indices\nend_header\n"
           "0 0 0 " + colors + "\n1 0 0 " + colors + "\n1 1 0 " + colors + "\n0 1 0 " + colors + "\n3 0 1 2\n3 0 2 3\n";
}

TEST_F(MeshIoTest, PlyVertexColorsTintTheModel) {
    // 8-bit colors are sRGB (128 is 0.216 linear); float colors are taken as linear values.
    const TriangleMesh bytes = loadMesh(write("bytes.ply", coloredSquarePly("uchar", "255 128 0")));
    ASSERT_EQ(bytes.colors.size(), 4u);
    EXPECT_NEAR(bytes.colors[0].r, 1.0f, 1e-6f);
    EXPECT_NEAR(bytes.colors[0].g, 0.2158605f, 1e-5f);
    EXPECT_EQ(bytes.colors[0].b, 0.0f);
    const TriangleMesh floats = loadMesh(write("floats.ply", coloredSquarePly("float", "0.1 0.2 0.9")));
    EXPECT_EQ(floats.colors[3], glm::vec3(0.1f, 0.2f, 0.9f));
    const glm::vec3 shown = modelColor(loadSceneOrMesh(write("shown.ply", coloredSquarePly("uchar", "20 40 230")), 48, 48,
                                                       MeshFraming::Showcase));
    EXPECT_GT(shown.b, 4 * shown.r);
}

TEST_F(MeshIoTest, ShowcaseReadsGltfBaseColorImages) {
    // An image red in its top half, blue in the bottom; every uv of the triangle is (0.5, 0.1), which in
    // glTF (v down the image) is near the top: red. The image as a file of its own, as a data URI and in
    // a buffer view (as GLB files hold them).
    Image halves(8, 8, 3);
    for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 8; ++x) halves.at(x, y)[y < 4 ? 0 : 2] = 1.0f;
    writeImage(halves, dir_ / "halves.png", true);
    std::ifstream pngFile(dir_ / "halves.png", std::ios::binary);
    const std::string png((std::istreambuf_iterator<char>(pngFile)), std::istreambuf_iterator<char>());
    std::string buffer;
    for (float value : {0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 0.f, 1.f, 0.f}) appendBinary(buffer, value, false);
    for (int i = 0; i < 3; ++i)
        for (float value : {0.5f, 0.1f}) appendBinary(buffer, value, false);
    for (uint16_t index : {0, 1, 2}) appendBinary(buffer, index, false);
    buffer += std::string(2, '\0') + png;  // the image's view starts at 68
    auto gltf = [&](const std::string& images, size_t imageViewLength) {
        return R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
  "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "TEXCOORD_0": 1}, "indices": 2, "material": 0}]}],
  "materials": [{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}],
  "textures": [{"source": 0}], "images": [)" + images + R"(],
  "accessors": [
    {"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0,0,0], "max": [1,1,0]},
    {"bufferView": 1, "componentType": 5126, "count": 3, "type": "VEC2"},
    {"bufferView": 2, "componentType": 5123, "count": 3, "type": "SCALAR"}],
  "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 36}, {"buffer": 0, "byteOffset": 36, "byteLength": 24},
                  {"buffer": 0, "byteOffset": 60, "byteLength": 6}, {"buffer": 0, "byteOffset": 68, "byteLength": )" +
               std::to_string(imageViewLength) + R"(}],
  "buffers": [{"byteLength": )" + std::to_string(buffer.size()) + R"(, "uri": "data:application/octet-stream;base64,)" +
               base64(buffer) + "\"}]}";
    };
    for (const std::string& images : {std::string(R"({"uri": "halves.png"})"),
                                      R"({"uri": "data:image/png;base64,)" + base64(png) + "\"}",
                                      std::string(R"({"bufferView": 3, "mimeType": "image/png"})")}) {
        const SceneDescription scene = loadSceneOrMesh(write("textured.gltf", gltf(images, png.size())), 48, 48, MeshFraming::Showcase);
        EXPECT_TRUE(scene.warnings.empty()) << scene.warnings[0];
        const glm::vec3 color = modelColor(scene);
        EXPECT_GT(color.r, 4 * color.b) << images;
    }
    // A view past the end of its buffer is refused by name; bytes that are no image leave the base color.
    try {
        loadSceneOrMesh(write("past.gltf", gltf(R"({"bufferView": 3, "mimeType": "image/png"})", png.size() + 1)), 48, 48,
                        MeshFraming::Showcase);
        ADD_FAILURE() << "a view past its buffer was read";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("images[0]: its bufferView runs past the end of its buffer"), std::string::npos) << e.what();
    }
    const SceneDescription broken = loadSceneOrMesh(write("broken.gltf", gltf(R"({"bufferView": 1, "mimeType": "image/png"})", png.size())),
                                                    48, 48, MeshFraming::Showcase);
    ASSERT_EQ(broken.warnings.size(), 1u);
    EXPECT_NE(broken.warnings[0].find("broken.gltf:images[0].png"), std::string::npos) << broken.warnings[0];
}

} // namespace
} // namespace wideray
