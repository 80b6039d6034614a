#include "accel/triangle_splitter.h"

#include <cmath>

namespace wideray {
namespace {

__m128 load(const glm::vec3& v) { return _mm_setr_ps(v.x, v.y, v.z, 0.0f); }

} // namespace

void TriangleSplitter::split(uint32_t prim, const BuildBox& box, int axis, float position, BuildBox& left,
                             BuildBox& right) const {
    const glm::uvec3& t = mesh_.triangles[prim];
    const glm::vec3 v[3] = {mesh_.positions[t.x], mesh_.positions[t.y], mesh_.positions[t.z]};
    left = right = BuildBox();
    for (int i = 0; i < 3; ++i) {
        const glm::vec3& a = v[i];
        const glm::vec3& b = v[(i + 1) % 3];
        if (a[axis] <= position) left.grow(load(a));
        if (a[axis] >= position) right.grow(load(a));
        if ((a[axis] < position && b[axis] > position) || (a[axis] > position && b[axis] < position)) {
            const float s = (position - a[axis]) / (b[axis] - a[axis]);
            glm::vec3 p = a + s * (b - a);
            // The lerp is off by a few ulps of the endpoints' magnitude; the plane coordinate is exact.
            glm::vec3 slack = (glm::abs(a) + glm::abs(b)) * 0x1p-20f;
            p[axis] = position;
            slack[axis] = 0.0f;
            const BuildBox crossing(load(p - slack), load(p + slack));
            left.grow(crossing);
            right.grow(crossing);
        }
    }
    left.intersect(box);
    right.intersect(box);
    if (left.empty()) left = BuildBox();
    if (right.empty()) right = BuildBox();
}

} // namespace wideray
