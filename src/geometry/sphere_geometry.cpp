#include "geometry/sphere_geometry.h"

#include <cmath>

namespace wideray {

Bounds3f SphereGeometry::primitiveBounds(uint32_t primId) const {
    const Sphere& s = spheres_[primId];
    return {s.center - glm::vec3(s.radius), s.center + glm::vec3(s.radius)};
}

// The quadratic is solved in double from the origin relative to the center, which keeps both roots
// accurate for rays starting far away or on the surface.
bool SphereGeometry::intersect(const Ray& ray, uint32_t primId, float tfar, float& t, float& u, float& v) const {
    const Sphere& s = spheres_[primId];
    double ox = double(ray.ox) - s.center.x, oy = double(ray.oy) - s.center.y, oz = double(ray.oz) - s.center.z;
    double dx = ray.dx, dy = ray.dy, dz = ray.dz;
    double a = dx * dx + dy * dy + dz * dz;
    double b = ox * dx + oy * dy + oz * dz;
    double r = s.radius;
    // Discriminant computed as |o x d|-based form (Haines et al., Ray Tracing Gems ch. 7) for precision.
    double fx = ox - b / a * dx, fy = oy - b / a * dy, fz = oz - b / a * dz;
    double disc = a * (r * r - (fx * fx + fy * fy + fz * fz));
    if (disc < 0) return false;
    double q = -b - std::copysign(std::sqrt(disc), b);
    double t0 = q / a, t1 = q != 0 ? (ox * ox + oy * oy + oz * oz - r * r) / q : t0;
    if (t0 > t1) std::swap(t0, t1);
    double tHit = t0 >= ray.tnear ? t0 : t1;
    if (!(tHit >= ray.tnear && tHit <= tfar)) return false;
    t = float(tHit);
    if (!(t >= ray.tnear && t <= tfar)) return false;
    u = v = 0.0f;
    return true;
}

SurfacePoint SphereGeometry::surface(const Ray& ray, const Hit& hit) const {
    const Sphere& s = spheres_[hit.primId];
    glm::vec3 p = glm::vec3(ray.ox, ray.oy, ray.oz) + hit.t * glm::vec3(ray.dx, ray.dy, ray.dz);
    glm::vec3 n = glm::normalize(p - s.center);
    SurfacePoint sp;
    sp.position = s.center + n * s.radius;
    sp.geometricNormal = sp.shadingNormal = n;
    sp.uv = {0.5f + std::atan2(n.z, n.x) / (2.0f * float(M_PI)), std::acos(glm::clamp(n.y, -1.0f, 1.0f)) / float(M_PI)};
    sp.material = s.material;
    return sp;
}

} // namespace wideray
