#pragma once
// The analytic primitives of the scene (core/scene.h, AnalyticObject) as user geometry: each ray is
// taken into the primitive's object space by the inverse of its transform, intersected there with the
// canonical surface in double precision (quadrics by their quadratic, the torus by its quartic,
// solved robustly and refined on the torus' own equation, blobs by the degree-6 polynomial their
// field is between the points where the ray enters and leaves a ball), and its normal brought back
// by the inverse transpose. t is the same in both spaces (the direction is transformed, not normalized).
#include <vector>

#include <glm/glm.hpp>

#include "core/geometry.h"
#include "core/scene.h"
#include "geometry/object_space.h"

namespace wideray {

class AnalyticGeometry final : public UserGeometry {
public:
    explicit AnalyticGeometry(const std::vector<AnalyticObject>& objects);

    uint32_t primitiveCount() const override { return uint32_t(objects_.size()); }
    Bounds3f primitiveBounds(uint32_t primId) const override { return objects_[primId].worldBounds; }
    /// u receives which part was hit (0: the surface, 1: the cap at y = -1 or the low end, 2: the cap
    /// at the high end), for surface().
    bool intersect(const Ray& ray, uint32_t primId, float tfar, float& t, float& u, float& v) const override;
    SurfacePoint surface(const Ray& ray, const Hit& hit) const override;

    /// A quadric's value at an object-space point: negative inside.
    struct Quadric {
        double a, b, c, d, e, f, g, h, i, j;  ///< a x^2 + b y^2 + c z^2 + d xy + e xz + f yz + g x + h y + i z + j
        double at(const glm::dvec3& p) const;
        glm::dvec3 gradient(const glm::dvec3& p) const;
    };

private:
    struct Object {
        AnalyticObject model;
        ObjectSpace space;
        Quadric quadric{};         ///< the quadrics (within -1 <= y <= 1, capped there where capped)
        glm::dvec3 lower{0.0}, upper{0.0};  ///< the object-space box
        Bounds3f worldBounds{};
    };

    /// Candidate distances along the object-space ray (o, d) in [tnear, tfar], with the part hit.
    bool intersectObject(const Object& object, const glm::dvec3& o, const glm::dvec3& d, double tnear, double tfar,
                         double& t, int& part) const;

    /// A blob over [t0, t1] (within its box): the first crossing of its threshold.
    static bool intersectBlob(const AnalyticObject& blob, const glm::dvec3& o, const glm::dvec3& d, double t0, double t1,
                              double& t, int& part);

    std::vector<Object> objects_;
};

} // namespace wideray
