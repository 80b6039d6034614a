#pragma once
// Clips triangles for spatial splits: the boxes of the parts of a triangle on either side of a plane,
// within the box its reference already has.
#include "accel/build_ref.h"
#include "core/mesh.h"

namespace wideray {

/// One triangle's vertices, loaded once for the several planes a reference is split by.
class SplitTriangle {
public:
    SplitTriangle(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c)
        : v_{load(a), load(b), load(c)}, coord_{{a.x, a.y, a.z}, {b.x, b.y, b.z}, {c.x, c.y, c.z}} {}

    /// `left` and `right` bound the parts of the triangle inside `box` below and above the plane
    /// x[axis] = position (an empty box for a side without any). Conservative: a crossing point's
    /// rounding is covered by a few ulps of slack, so the two boxes hold every point of the part.
    void split(const BuildBox& box, int axis, float position, BuildBox& left, BuildBox& right) const {
        left = right = BuildBox();
        for (int i = 0; i < 3; ++i) {
            const int j = i == 2 ? 0 : i + 1;
            const float a = coord_[i][axis], b = coord_[j][axis];
            if (a <= position) left.grow(v_[i]);
            if (a >= position) right.grow(v_[i]);
            if ((a < position && b > position) || (a > position && b < position)) {
                const __m128 s = _mm_set1_ps((position - a) / (b - a));
                const __m128 p = _mm_add_ps(v_[i], _mm_mul_ps(s, _mm_sub_ps(v_[j], v_[i])));
                // The lerp is off by a few ulps of the endpoints' magnitude; the plane coordinate is exact.
                const __m128 absMask = _mm_castsi128_ps(_mm_set1_epi32(0x7fffffff));
                __m128 slack = _mm_mul_ps(_mm_add_ps(_mm_and_ps(v_[i], absMask), _mm_and_ps(v_[j], absMask)),
                                          _mm_set1_ps(0x1p-20f));
                alignas(16) float lo[4], hi[4];
                _mm_store_ps(lo, _mm_sub_ps(p, slack));
                _mm_store_ps(hi, _mm_add_ps(p, slack));
                lo[axis] = hi[axis] = position;
                const BuildBox crossing(_mm_load_ps(lo), _mm_load_ps(hi));
                left.grow(crossing);
                right.grow(crossing);
            }
        }
        left.intersect(box);
        right.intersect(box);
        if (left.empty()) left = BuildBox();
        if (right.empty()) right = BuildBox();
    }

private:
    static __m128 load(const glm::vec3& v) { return _mm_setr_ps(v.x, v.y, v.z, 0.0f); }

    __m128 v_[3];
    float coord_[3][3];
};

/// The triangles of a mesh, for the builder to clip by index.
class TriangleSplitter {
public:
    explicit TriangleSplitter(const TriangleMesh& mesh) : mesh_(mesh) {}

    SplitTriangle triangle(uint32_t prim) const {
        const glm::uvec3& t = mesh_.triangles[prim];
        return {mesh_.positions[t.x], mesh_.positions[t.y], mesh_.positions[t.z]};
    }

private:
    const TriangleMesh& mesh_;
};

} // namespace wideray
