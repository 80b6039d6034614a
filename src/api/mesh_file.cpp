// loadMeshFile (include/wideray/mesh_file.h): the CLI's mesh loaders, their result as flat arrays.
#include "wideray/mesh_file.h"

#include "core/error.h"
#include "io/mesh_io.h"
#include "wideray/error.h"

namespace wideray {

MeshArrays loadMeshFile(const std::string& path) {
    TriangleMesh mesh;
    try {
        mesh = loadMesh(path);
    } catch (const InputError& e) {
        throw Error(e.what());
    }
    MeshArrays arrays;
    arrays.positions.reserve(3 * mesh.positions.size());
    for (const glm::vec3& p : mesh.positions) arrays.positions.insert(arrays.positions.end(), {p.x, p.y, p.z});
    arrays.indices.reserve(3 * mesh.triangles.size());
    for (const glm::uvec3& t : mesh.triangles) arrays.indices.insert(arrays.indices.end(), {t.x, t.y, t.z});
    return arrays;
}

} // namespace wideray
