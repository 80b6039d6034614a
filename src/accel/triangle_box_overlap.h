#pragma once
// Whether a triangle touches a box: the separating axis test of Akenine-Moeller (2001, "Fast 3D
// triangle-box overlap testing"): the box's three axes, the triangle's normal and the nine cross
// products of edges and axes. In double, on float input, so that rounding never separates a
// triangle from a box it touches; touching counts as overlapping.
#include <algorithm>
#include <cmath>

#include <glm/glm.hpp>

namespace wideray {

inline bool triangleOverlapsBox(const glm::dvec3& lower, const glm::dvec3& upper, glm::dvec3 a, glm::dvec3 b,
                                glm::dvec3 c) {
    const glm::dvec3 center = 0.5 * (lower + upper), half = 0.5 * (upper - lower);
    a -= center;
    b -= center;
    c -= center;
    // The box's axes: the triangle's box against the box.
    for (int i = 0; i < 3; ++i)
        if (std::min({a[i], b[i], c[i]}) > half[i] || std::max({a[i], b[i], c[i]}) < -half[i]) return false;
    const glm::dvec3 edges[3] = {b - a, c - b, a - c};
    // The nine edge-axis cross products.
    for (int i = 0; i < 3; ++i) {
        for (const glm::dvec3& e : edges) {
            glm::dvec3 axis(0.0);
            axis[(i + 1) % 3] = -e[(i + 2) % 3];
            axis[(i + 2) % 3] = e[(i + 1) % 3];
            const double pa = glm::dot(a, axis), pb = glm::dot(b, axis), pc = glm::dot(c, axis);
            const double r = half.x * std::fabs(axis.x) + half.y * std::fabs(axis.y) + half.z * std::fabs(axis.z);
            if (std::min({pa, pb, pc}) > r || std::max({pa, pb, pc}) < -r) return false;
        }
    }
    // The triangle's plane.
    const glm::dvec3 n = glm::cross(edges[0], edges[1]);
    const double d = glm::dot(n, a);
    const double r = half.x * std::fabs(n.x) + half.y * std::fabs(n.y) + half.z * std::fabs(n.z);
    return std::fabs(d) <= r;
}

} // namespace wideray
