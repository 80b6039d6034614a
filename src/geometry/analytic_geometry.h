#pragma once
// The analytic primitives of the scene (core/scene.h, AnalyticObject) as user geometry: each ray is
// taken into the primitive's object space by the inverse of its transform, intersected there with the
// canonical surface in double precision (quadrics by their quadratic, the torus by its quartic,
// solved robustly and refined on the torus' own equation, blobs by the degree-6 polynomial their
// field is between the points where the ray enters and leaves a ball), and its normal brought back
// by the inverse transpose. t is the same in both spaces (the direction is transformed, not normalized).
#include <optional>
#include <vector>

#include <glm/glm.hpp>

#include "core/geometry.h"
#include "core/scene.h"
#include "geometry/object_space.h"
#include "geometry/solid_crossing.h"

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

    /// Appends where the ray's whole line (any t) crosses the boundary of the solid primId, in
    /// increasing t: the surface roots where the solid's inside changes (tangent roots dropped).
    /// Closed solids only: capped quadrics other than the general quadric, the torus and blobs.
    void crossings(uint32_t primId, const Ray& ray, SolidCrossings& out) const;

    /// A quadric's value at an object-space point: negative inside.
    struct Quadric {
        double a, b, c, d, e, f, g, h, i, j;  ///< a x^2 + b y^2 + c z^2 + d xy + e xz + f yz + g x + h y + i z + j
        double at(const glm::dvec3& p) const;
        glm::dvec3 gradient(const glm::dvec3& p) const;
    };

private:
    struct Object {
        AnalyticObject model;
        ObjectSpace space;  ///< at time 0 (the only one unless model.endTransform)
        Quadric quadric{};         ///< the quadrics (within -1 <= y <= 1, capped there where capped)
        glm::dvec3 lower{0.0}, upper{0.0};  ///< the object-space box
        Bounds3f worldBounds{};
    };

    /// Calls visit(t, part) for the surface's roots along the object-space ray (o, d) in [tnear, tfar]:
    /// in no particular order, except blobs, whose roots come in increasing t and stop when visit
    /// returns false.
    template <class Visit>
    void visitRoots(const Object& object, const glm::dvec3& o, const glm::dvec3& d, double tnear, double tfar,
                    Visit&& visit) const;

    /// A blob over [t0, t1] (within its box): its threshold's crossings, in increasing t.
    template <class Visit>
    static void visitBlobRoots(const AnalyticObject& blob, const glm::dvec3& o, const glm::dvec3& d, double t0, double t1,
                               Visit&& visit);

    /// The object's space at the ray's time: its own unless it moves (then made in `moving`).
    static const ObjectSpace& spaceAt(const Object& object, float time, std::optional<ObjectSpace>& moving);

    /// Whether the object-space point lies inside the solid.
    static bool contains(const Object& object, const glm::dvec3& p);

    std::vector<Object> objects_;
};

} // namespace wideray
