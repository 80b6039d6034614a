#include "accel/primitive_table.h"

#include <stdexcept>

#include "core/error.h"

namespace wideray {

PrimitiveTable::PrimitiveTable(const SceneGeometry& geometry) {
    for (uint32_t g = 0; g < geometry.size(); ++g) {
        const Geometry& item = geometry[g];
        if (item.instances())
            throw InputError("--accel", "", "the course's structures are single-level: trace two-level instances with bvh4, "
                                            "bvh8 or Embree, or flatten them (--instancing flatten; moving instances "
                                            "cannot be flattened)");
        geometries_.push_back(item.user());
        if (const TriangleMesh* mesh = item.triangles()) {
            if (g != 0) throw std::logic_error("PrimitiveTable: triangle meshes must be geometry 0");
            triangles_.reserve(mesh->triangles.size());
            for (const glm::uvec3& t : mesh->triangles) {
                const glm::vec3 &a = mesh->positions[t.x], &b = mesh->positions[t.y], &c = mesh->positions[t.z];
                triangles_.push_back({a.x, a.y, a.z, b.x, b.y, b.z, c.x, c.y, c.z});
                Bounds3f box;
                box.grow(a);
                box.grow(b);
                box.grow(c);
                boxes_.push_back(box);
            }
        }
    }
    for (uint32_t g = 0; g < geometry.size(); ++g)
        for (uint32_t p = 0; geometries_[g] && p < geometries_[g]->primitiveCount(); ++p) {
            users_.push_back({g, p});
            boxes_.push_back(geometries_[g]->primitiveBounds(p));
        }
    if (boxes_.size() >= (size_t(1) << 31)) throw std::length_error("PrimitiveTable: too many primitives");
    for (const Bounds3f& b : boxes_) bounds_.grow(b);
}

SplitTriangle PrimitiveTable::triangle(uint32_t item) const {
    const TriangleVertices& t = triangles_[item];
    return {{t.v0x, t.v0y, t.v0z}, {t.v1x, t.v1y, t.v1z}, {t.v2x, t.v2y, t.v2z}};
}

PrimitiveView PrimitiveTable::view() const {
    return {triangles_.data(), uint32_t(triangles_.size()), users_.data(), geometries_.data()};
}

size_t PrimitiveTable::bytes() const {
    return triangles_.size() * sizeof(TriangleVertices) + users_.size() * sizeof(PrimRef);
}

} // namespace wideray
