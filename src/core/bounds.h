#pragma once
// Axis-aligned bounding boxes for BVH construction.
#include <algorithm>
#include <limits>

#include <glm/glm.hpp>

namespace wideray {

struct Bounds3f {
    glm::vec3 lower{std::numeric_limits<float>::infinity()};
    glm::vec3 upper{-std::numeric_limits<float>::infinity()};

    Bounds3f() = default;
    Bounds3f(const glm::vec3& lo, const glm::vec3& hi) : lower(lo), upper(hi) {}

    void grow(const glm::vec3& p) { lower = glm::min(lower, p); upper = glm::max(upper, p); }
    void grow(const Bounds3f& b) { lower = glm::min(lower, b.lower); upper = glm::max(upper, b.upper); }

    bool empty() const { return lower.x > upper.x || lower.y > upper.y || lower.z > upper.z; }
    glm::vec3 extent() const { return upper - lower; }
    glm::vec3 center() const { return 0.5f * (lower + upper); }

    /// Surface area; 0 for an empty box.
    float area() const {
        if (empty()) return 0.0f;
        glm::vec3 e = extent();
        return 2.0f * (e.x * e.y + e.y * e.z + e.z * e.x);
    }

    int largestAxis() const {
        glm::vec3 e = extent();
        return e.x >= e.y && e.x >= e.z ? 0 : (e.y >= e.z ? 1 : 2);
    }

    bool contains(const Bounds3f& b) const {
        return glm::all(glm::lessThanEqual(lower, b.lower)) && glm::all(glm::greaterThanEqual(upper, b.upper));
    }
};

} // namespace wideray
