#pragma once
// An object placed by an affine transform, as the analytic primitives and height fields are: rays
// taken into its object space in double (the direction is not normalized, so t is the same in both
// spaces), points back to the world, normals by the inverse transpose, its world box from its
// object-space box, and the ray's interval through an object-space box.
#include <algorithm>
#include <optional>

#include <glm/glm.hpp>

#include "core/bounds.h"
#include "core/ray.h"

namespace wideray {

struct ObjectSpace {
    glm::dmat4 toWorld, toObject;
    glm::dmat3 normalToWorld;  ///< the inverse transpose of the transform's linear part

    explicit ObjectSpace(const glm::dmat4& objectToWorld)
        : toWorld(objectToWorld), toObject(glm::inverse(toWorld)), normalToWorld(glm::transpose(glm::dmat3(toObject))) {}
    explicit ObjectSpace(const glm::mat4& objectToWorld) : ObjectSpace(glm::dmat4(objectToWorld)) {}

    /// A moving object's space at `time` in [0, 1]: its transforms interpolated entry by entry.
    static ObjectSpace at(const glm::mat4& start, const glm::mat4& end, float time) {
        return ObjectSpace((1.0 - double(time)) * glm::dmat4(start) + double(time) * glm::dmat4(end));
    }

    void ray(const Ray& r, glm::dvec3& o, glm::dvec3& d) const {
        o = glm::dvec3(toObject * glm::dvec4(r.ox, r.oy, r.oz, 1.0));
        d = glm::dmat3(toObject) * glm::dvec3(r.dx, r.dy, r.dz);
    }

    glm::vec3 point(const glm::dvec3& p) const { return glm::vec3(toWorld * glm::dvec4(p, 1.0)); }

    /// The unit world normal of an object-space normal (any length; +y if it is zero).
    glm::vec3 normal(const glm::dvec3& n) const {
        const glm::dvec3 w = normalToWorld * n;
        const double length = glm::length(w);
        return length > 0.0 ? glm::vec3(w / length) : glm::vec3(0.0f, 1.0f, 0.0f);
    }

    /// The world box of the object-space box's corners (exact for an affine transform), grown by a
    /// little for the rounding to float.
    Bounds3f bounds(const glm::dvec3& lower, const glm::dvec3& upper) const {
        Bounds3f b;
        for (int corner = 0; corner < 8; ++corner)
            b.grow(point({(corner & 1) ? upper.x : lower.x, (corner & 2) ? upper.y : lower.y,
                          (corner & 4) ? upper.z : lower.z}));
        const glm::vec3 pad = 1e-6f * (glm::abs(b.lower) + glm::abs(b.upper)) + 1e-30f;
        return {b.lower - pad, b.upper + pad};
    }
};

/// The world box of an object-space box over a motion: the boxes at both ends hold it throughout,
/// each corner moving on a straight line between its two positions.
inline Bounds3f motionBounds(const glm::mat4& start, const std::optional<glm::mat4>& end, const glm::dvec3& lower,
                             const glm::dvec3& upper) {
    Bounds3f b = ObjectSpace(start).bounds(lower, upper);
    if (end) b.grow(ObjectSpace(*end).bounds(lower, upper));
    return b;
}

/// Narrows [t0, t1] to the object-space ray's part inside the box [lower, upper]; false when none is.
inline bool boxInterval(const glm::dvec3& lower, const glm::dvec3& upper, const glm::dvec3& o, const glm::dvec3& d,
                        double& t0, double& t1) {
    for (int a = 0; a < 3; ++a) {
        if (d[a] == 0.0) {
            if (o[a] < lower[a] || o[a] > upper[a]) return false;
            continue;
        }
        double n = (lower[a] - o[a]) / d[a], f = (upper[a] - o[a]) / d[a];
        if (n > f) std::swap(n, f);
        t0 = std::max(t0, n);
        t1 = std::min(t1, f);
    }
    return t0 <= t1;
}

} // namespace wideray
