#pragma once
// Height fields (core/scene.h, HeightField) as user geometry, traced directly: the ray, taken into
// object space, walks the field's tiles of kTileCells x kTileCells cells in a 2D DDA, skips every
// tile whose height range its own does not meet, and walks the cells of the others, testing each
// cell's two triangles (the triangulation of io/terrain.h's heightFieldMesh) in double precision.
#include <vector>

#include <glm/glm.hpp>

#include "core/geometry.h"
#include "core/scene.h"
#include "geometry/object_space.h"

namespace wideray {

class HeightFieldGeometry final : public UserGeometry {
public:
    static constexpr int kTileCells = 8;

    explicit HeightFieldGeometry(const std::vector<HeightField>& fields);
    HeightFieldGeometry(const HeightFieldGeometry&) = delete;  // its fields point into models_
    HeightFieldGeometry& operator=(const HeightFieldGeometry&) = delete;

    uint32_t primitiveCount() const override { return uint32_t(fields_.size()); }
    Bounds3f primitiveBounds(uint32_t primId) const override { return fields_[primId].worldBounds; }
    /// u, v receive the cell and triangle hit, for surface().
    bool intersect(const Ray& ray, uint32_t primId, float tfar, float& t, float& u, float& v) const override;
    SurfacePoint surface(const Ray& ray, const Hit& hit) const override;

private:
    struct Field {
        const HeightField* model;
        ObjectSpace space;
        int tiles = 0;                          ///< per side
        std::vector<float> tileLow{}, tileHigh{};  ///< each tile's height range
        double low = 0, high = 0;               ///< the whole field's
        Bounds3f worldBounds{};
    };

    double height(const Field& f, int i, int j) const;
    /// The triangle `which` (0: above the diagonal in x, 1: in z) of cell (i, j): its vertices.
    void cellTriangle(const Field& f, int i, int j, int which, glm::dvec3& a, glm::dvec3& b, glm::dvec3& c) const;

    std::vector<HeightField> models_;
    std::vector<Field> fields_;
};

} // namespace wideray
