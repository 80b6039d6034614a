// Wavefront OBJ (+ MTL) loading through tinyobjloader.
#include <fstream>
#include <iostream>
#include <unordered_map>

#include <tiny_obj_loader.h>

#include "core/error.h"
#include "io/mesh_io.h"

namespace wideray {
namespace {

/// tinyobj's own triangulation cuts quads along the shorter diagonal and ear-clips larger polygons;
/// we read polygons as they are and fan-triangulate them, as the rest of wideray expects.
tinyobj::ObjReaderConfig untriangulatedConfig() {
    tinyobj::ObjReaderConfig config;
    config.triangulate = false;
    config.vertex_color = false;
    return config;
}

std::string stripNewline(std::string s) {
    while (!s.empty() && (s.back() == '\n' || s.back() == '\r')) s.pop_back();
    return s;
}

void printWarnings(const std::string& file, const std::string& warnings) {
    if (!warnings.empty()) std::cerr << "warning: " << file << ": " << stripNewline(warnings) << "\n";
}

struct ObjFace {
    const tinyobj::shape_t& shape;
    size_t faceIndex;
};

/// Normals and uvs are kept only when every corner of every face has them.
struct CornerAttributes {
    bool normals = true;
    bool uvs = true;
};

CornerAttributes attributesOnEveryCorner(const tinyobj::ObjReader& reader) {
    CornerAttributes present;
    present.normals = !reader.GetAttrib().normals.empty();
    present.uvs = !reader.GetAttrib().texcoords.empty();
    for (const tinyobj::shape_t& shape : reader.GetShapes()) {
        for (const tinyobj::index_t& corner : shape.mesh.indices) {
            present.normals = present.normals && corner.normal_index >= 0;
            present.uvs = present.uvs && corner.texcoord_index >= 0;
        }
    }
    return present;
}

void checkIndex(int index, size_t count, const char* what, const ObjFace& face, const std::string& file) {
    if (index < 0 || size_t(index) >= count)
        throw InputError(file, "shape '" + face.shape.name + "' face " + std::to_string(face.faceIndex),
                         std::string(what) + " index " + std::to_string(index + 1) + " out of range (the file has " +
                             std::to_string(count) + ")");
}

/// Builds output vertices from OBJ corners: positions are shared directly when there are no
/// normals or uvs; otherwise one vertex is made per distinct (position, normal, uv) triple.
class VertexBuilder {
public:
    VertexBuilder(const tinyobj::attrib_t& attrib, CornerAttributes use, TriangleMesh& mesh)
        : attrib_(attrib), use_(use), mesh_(mesh) {
        const size_t positionCount = attrib.vertices.size() / 3;
        if (!use.normals && !use.uvs) {
            mesh.positions.resize(positionCount);
            for (size_t i = 0; i < positionCount; ++i) mesh.positions[i] = position(int(i));
        }
    }

    uint32_t vertexFor(const tinyobj::index_t& corner, const ObjFace& face, const std::string& file) {
        checkIndex(corner.vertex_index, attrib_.vertices.size() / 3, "vertex", face, file);
        if (use_.normals) checkIndex(corner.normal_index, attrib_.normals.size() / 3, "normal", face, file);
        if (use_.uvs) checkIndex(corner.texcoord_index, attrib_.texcoords.size() / 2, "texture coordinate", face, file);
        if (!use_.normals && !use_.uvs) return uint32_t(corner.vertex_index);

        const Key key{corner.vertex_index, use_.normals ? corner.normal_index : -1,
                      use_.uvs ? corner.texcoord_index : -1};
        auto [it, inserted] = vertexOfCorner_.try_emplace(key, uint32_t(mesh_.positions.size()));
        if (inserted) {
            mesh_.positions.push_back(position(key.position));
            if (use_.normals) {
                const float* n = &attrib_.normals[3 * size_t(key.normal)];
                mesh_.normals.emplace_back(n[0], n[1], n[2]);
            }
            if (use_.uvs) {
                const float* uv = &attrib_.texcoords[2 * size_t(key.uv)];
                mesh_.uvs.emplace_back(uv[0], uv[1]);
            }
        }
        return it->second;
    }

private:
    struct Key {
        int position, normal, uv;
        bool operator==(const Key&) const = default;
    };
    struct KeyHash {
        size_t operator()(const Key& k) const {
            return std::hash<uint64_t>()((uint64_t(uint32_t(k.position)) << 32) ^
                                         (uint64_t(uint32_t(k.normal)) << 16) ^ uint32_t(k.uv));
        }
    };

    glm::vec3 position(int i) const {
        const float* p = &attrib_.vertices[3 * size_t(i)];
        return {p[0], p[1], p[2]};
    }

    const tinyobj::attrib_t& attrib_;
    CornerAttributes use_;
    TriangleMesh& mesh_;
    std::unordered_map<Key, uint32_t, KeyHash> vertexOfCorner_;
};

/// Maps tinyobj material ids to mesh materials; faces without one share a material named "default".
class MaterialTable {
public:
    MaterialTable(const std::vector<tinyobj::material_t>& objMaterials, TriangleMesh& mesh)
        : mesh_(mesh), objMaterialCount_(objMaterials.size()) {
        for (const tinyobj::material_t& m : objMaterials)
            mesh.materials.push_back({m.name, {m.diffuse[0], m.diffuse[1], m.diffuse[2]}, m.diffuse_texname});
    }

    bool any() const { return objMaterialCount_ > 0; }

    uint32_t indexFor(int materialId) {
        if (materialId >= 0 && size_t(materialId) < objMaterialCount_) return uint32_t(materialId);
        if (mesh_.materials.size() == objMaterialCount_) mesh_.materials.push_back({"default", MeshMaterial{}.diffuse});
        return uint32_t(objMaterialCount_);
    }

private:
    TriangleMesh& mesh_;
    size_t objMaterialCount_;
};

TriangleMesh meshFromReader(const tinyobj::ObjReader& reader, bool parsed, const std::string& file) {
    printWarnings(file, reader.Warning());
    if (!parsed || !reader.Error().empty()) throw InputError(file, "", stripNewline(reader.Error()));

    TriangleMesh mesh;
    VertexBuilder vertices(reader.GetAttrib(), attributesOnEveryCorner(reader), mesh);
    MaterialTable materials(reader.GetMaterials(), mesh);
    const bool withMaterials = materials.any();

    for (const tinyobj::shape_t& shape : reader.GetShapes()) {
        const tinyobj::mesh_t& polygons = shape.mesh;
        size_t firstCorner = 0;
        for (size_t f = 0; f < polygons.num_face_vertices.size(); ++f) {
            const ObjFace face{shape, f};
            const size_t cornerCount = polygons.num_face_vertices[f];
            // tinyobj stores polygon sizes in a byte (and drops faces of fewer than 3 corners), so a
            // size below 3 or a mismatch with the corner list means a polygon of 256 or more corners.
            if (cornerCount < 3 || firstCorner + cornerCount > polygons.indices.size())
                throw InputError(file, "shape '" + shape.name + "' face " + std::to_string(f),
                                 "polygon has more than 255 vertices");
            const uint32_t first = vertices.vertexFor(polygons.indices[firstCorner], face, file);
            uint32_t previous = vertices.vertexFor(polygons.indices[firstCorner + 1], face, file);
            for (size_t c = 2; c < cornerCount; ++c) {
                const uint32_t current = vertices.vertexFor(polygons.indices[firstCorner + c], face, file);
                mesh.triangles.emplace_back(first, previous, current);
                if (withMaterials) mesh.faceMaterial.push_back(materials.indexFor(polygons.material_ids[f]));
                previous = current;
            }
            firstCorner += cornerCount;
        }
        if (firstCorner != polygons.indices.size())
            throw InputError(file, "shape '" + shape.name + "'", "polygon has more than 255 vertices");
    }

    validateMesh(mesh, file);
    return mesh;
}

} // namespace

TriangleMesh loadObj(const std::filesystem::path& path) {
    const std::string file = path.string();
    if (!std::ifstream(path)) throw InputError(file, "", "cannot open file");
    tinyobj::ObjReader reader;
    const bool parsed = reader.ParseFromFile(file, untriangulatedConfig());
    return meshFromReader(reader, parsed, file);
}

TriangleMesh parseObj(const std::string& objText, const std::string& mtlText, const std::string& file) {
    tinyobj::ObjReader reader;
    const bool parsed = reader.ParseFromString(objText, mtlText, untriangulatedConfig());
    return meshFromReader(reader, parsed, file);
}

} // namespace wideray
