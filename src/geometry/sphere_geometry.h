#pragma once
// Spheres as user geometry, traced through the geometry interface.
#include <vector>

#include "core/geometry.h"
#include "core/scene.h"

namespace wideray {

class SphereGeometry final : public UserGeometry {
public:
    explicit SphereGeometry(std::vector<Sphere> spheres) : spheres_(std::move(spheres)) {}

    uint32_t primitiveCount() const override { return uint32_t(spheres_.size()); }
    Bounds3f primitiveBounds(uint32_t primId) const override;
    bool intersect(const Ray& ray, uint32_t primId, float tfar, float& t, float& u, float& v) const override;
    SurfacePoint surface(const Ray& ray, const Hit& hit) const override;

private:
    std::vector<Sphere> spheres_;
};

} // namespace wideray
