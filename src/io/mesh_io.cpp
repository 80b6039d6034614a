// Format dispatch and the checks every mesh loader shares.
#include "io/mesh_io.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <map>

#include "core/error.h"
#include "io/file_extension.h"

namespace wideray {

TriangleMesh loadMesh(const std::filesystem::path& path) {
    const std::string ext = lowercaseExtension(path);
    if (ext == ".obj") return loadObj(path);
    if (ext == ".ply") return loadPly(path);
    if (ext == ".gltf" || ext == ".glb") return loadGltf(path);
    throw InputError(path.string(), "",
                     "unknown mesh format '" + ext + "' (supported: .obj, .ply, .gltf, .glb)");
}

namespace {

bool isFinite(const glm::vec3& p) { return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z); }

bool hasZeroArea(const TriangleMesh& mesh, const glm::uvec3& t) {
    const glm::dvec3 a(mesh.positions[t.x]), b(mesh.positions[t.y]), c(mesh.positions[t.z]);
    const glm::dvec3 n = glm::cross(b - a, c - a);
    return n.x == 0.0 && n.y == 0.0 && n.z == 0.0;
}

} // namespace

void validateMesh(TriangleMesh& mesh, const std::string& file) {
    const size_t vertexCount = mesh.positions.size();
    for (size_t i = 0; i < vertexCount; ++i) {
        if (!isFinite(mesh.positions[i]))
            throw InputError(file, "vertex " + std::to_string(i), "coordinate is NaN or infinite");
    }
    for (size_t t = 0; t < mesh.triangles.size(); ++t) {
        for (int k = 0; k < 3; ++k) {
            const uint32_t index = mesh.triangles[t][k];
            if (index >= vertexCount)
                throw InputError(file, "triangle " + std::to_string(t),
                                 "vertex index " + std::to_string(index) + " out of range (" +
                                     std::to_string(vertexCount) + " vertices)");
        }
    }

    const bool withMaterials = !mesh.faceMaterial.empty();
    size_t kept = 0;
    for (size_t t = 0; t < mesh.triangles.size(); ++t) {
        if (hasZeroArea(mesh, mesh.triangles[t])) continue;
        mesh.triangles[kept] = mesh.triangles[t];
        if (withMaterials) mesh.faceMaterial[kept] = mesh.faceMaterial[t];
        ++kept;
    }
    mesh.droppedDegenerate += mesh.triangles.size() - kept;
    mesh.triangles.resize(kept);
    if (withMaterials) mesh.faceMaterial.resize(kept);

    if (mesh.triangles.empty())
        throw InputError(file, "", "no triangles (" + std::to_string(mesh.droppedDegenerate) +
                                       " zero-area triangles dropped)");
}

std::string closedSurfaceDefect(const TriangleMesh& mesh) {
    std::map<std::array<float, 3>, uint32_t> welded;
    std::vector<uint32_t> weldedIndex(mesh.positions.size());
    for (size_t i = 0; i < mesh.positions.size(); ++i) {
        const glm::vec3& p = mesh.positions[i];
        weldedIndex[i] = welded.emplace(std::array<float, 3>{p.x, p.y, p.z}, uint32_t(welded.size())).first->second;
    }
    std::map<std::pair<uint32_t, uint32_t>, int> edges;  // directed edge -> uses minus reverse uses
    for (const glm::uvec3& tri : mesh.triangles)
        for (int k = 0; k < 3; ++k) {
            const uint32_t a = weldedIndex[tri[k]], b = weldedIndex[tri[(k + 1) % 3]];
            if (a < b) ++edges[{a, b}];
            else --edges[{b, a}];
        }
    for (const auto& [edge, balance] : edges) {
        if (balance == 0) continue;
        std::vector<glm::vec3> corner(welded.size());
        for (const auto& [p, index] : welded) corner[index] = {p[0], p[1], p[2]};
        auto point = [&](uint32_t v) {
            const glm::vec3& p = corner[v];
            return "(" + std::to_string(p.x) + ", " + std::to_string(p.y) + ", " + std::to_string(p.z) + ")";
        };
        return "the surface is not closed: the edge " + point(edge.first) + " - " + point(edge.second) +
               " is not shared by two triangles of opposite winding";
    }
    return {};
}

} // namespace wideray
