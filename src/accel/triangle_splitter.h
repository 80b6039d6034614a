#pragma once
// Clips triangles for spatial splits: the boxes of the parts of a triangle on either side of a plane,
// within the box its reference already has.
#include "accel/build_ref.h"
#include "core/mesh.h"

namespace wideray {

/// One triangle's vertices, loaded once for the several planes a reference is split by.
class SplitTriangle {
public:
    SplitTriangle(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c) : v_{load(a), load(b), load(c)} {
        const __m128 absMask = _mm_castsi128_ps(_mm_set1_epi32(0x7fffffff));
        for (int i = 0; i < 3; ++i) {
            const int j = i == 2 ? 0 : i + 1;
            delta_[i] = _mm_sub_ps(v_[j], v_[i]);
            // The lerp is off by a few ulps of the endpoints' magnitude; the plane coordinate is exact.
            slack_[i] = _mm_mul_ps(_mm_add_ps(_mm_and_ps(v_[i], absMask), _mm_and_ps(v_[j], absMask)),
                                   _mm_set1_ps(0x1p-20f));
        }
        __m128 x = v_[0], y = v_[1], z = v_[2], w = _mm_setzero_ps();
        _MM_TRANSPOSE4_PS(x, y, z, w);
        along_[0] = x;
        along_[1] = y;
        along_[2] = z;
    }

    /// `left` and `right` bound the parts of the triangle inside `box` below and above the plane
    /// x[axis] = position (an empty box for a side without any). Conservative: a crossing point's
    /// rounding is covered by a few ulps of slack, so the two boxes hold every point of the part.
    /// Without branches on the vertices' sides, which no predictor learns.
    void split(const BuildBox& box, int axis, float position, BuildBox& left, BuildBox& right) const {
        const __m128 plane = _mm_set1_ps(position);
        const __m128 from = along_[axis];                                       // edge i starts at vertex i
        const __m128 to = _mm_shuffle_ps(from, from, _MM_SHUFFLE(3, 0, 2, 1));  // and ends at vertex i + 1
        const Sides sides{
            _mm_cmple_ps(from, plane), _mm_cmpge_ps(from, plane),
            _mm_or_ps(_mm_and_ps(_mm_cmplt_ps(from, plane), _mm_cmpgt_ps(to, plane)),
                      _mm_and_ps(_mm_cmpgt_ps(from, plane), _mm_cmplt_ps(to, plane))),
            _mm_div_ps(_mm_sub_ps(plane, from), _mm_sub_ps(to, from)), plane,
            BuildBox::axisMask(axis)};
        left = right = BuildBox();
        addVertexAndEdge<0>(sides, left, right);
        addVertexAndEdge<1>(sides, left, right);
        addVertexAndEdge<2>(sides, left, right);
        left.intersect(box);
        right.intersect(box);
        left = canonical(left);
        right = canonical(right);
    }

private:
    /// Per vertex (and the edge it starts) in lanes 0-2: below or on the plane, above or on it, the
    /// edge crossing it strictly, and where along the edge.
    struct Sides {
        __m128 below, above, crosses, t, plane, onAxis;
    };

    /// An empty box as BuildBox() has it (a part outside `box` can come out inverted on some axes
    /// only), without a branch: the binning grows bins by these parts.
    static BuildBox canonical(const BuildBox& b) {
        __m128 inverted = _mm_blend_ps(_mm_cmpgt_ps(b.lower, b.upper), _mm_setzero_ps(), 8);
        inverted = _mm_or_ps(inverted, _mm_shuffle_ps(inverted, inverted, _MM_SHUFFLE(1, 0, 3, 2)));
        inverted = _mm_or_ps(inverted, _mm_shuffle_ps(inverted, inverted, _MM_SHUFFLE(2, 3, 0, 1)));
        const BuildBox empty;
        return {_mm_blendv_ps(b.lower, empty.lower, inverted), _mm_blendv_ps(b.upper, empty.upper, inverted)};
    }

    template <int I>
    static __m128 broadcast(__m128 v) {
        return _mm_shuffle_ps(v, v, _MM_SHUFFLE(I, I, I, I));
    }

    static void growWhere(BuildBox& box, const BuildBox& part, __m128 mask) {
        box.lower = _mm_blendv_ps(box.lower, _mm_min_ps(box.lower, part.lower), mask);
        box.upper = _mm_blendv_ps(box.upper, _mm_max_ps(box.upper, part.upper), mask);
    }

    template <int I>
    void addVertexAndEdge(const Sides& s, BuildBox& left, BuildBox& right) const {
        const BuildBox vertex(v_[I], v_[I]);
        growWhere(left, vertex, broadcast<I>(s.below));
        growWhere(right, vertex, broadcast<I>(s.above));
        const __m128 p = _mm_add_ps(v_[I], _mm_mul_ps(broadcast<I>(s.t), delta_[I]));
        const BuildBox crossing(_mm_blendv_ps(_mm_sub_ps(p, slack_[I]), s.plane, s.onAxis),
                                _mm_blendv_ps(_mm_add_ps(p, slack_[I]), s.plane, s.onAxis));
        const __m128 crosses = broadcast<I>(s.crosses);
        growWhere(left, crossing, crosses);
        growWhere(right, crossing, crosses);
    }

    static __m128 load(const glm::vec3& v) { return _mm_setr_ps(v.x, v.y, v.z, 0.0f); }

    __m128 v_[3];
    __m128 delta_[3];  ///< edge i: from vertex i to vertex i + 1 (mod 3)
    __m128 slack_[3];
    __m128 along_[3];  ///< per axis, the three vertices' coordinates in lanes 0-2
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
