#pragma once
// Clips triangles for spatial splits: the boxes of the parts of a triangle on either side of a plane,
// within the box its reference already has.
#include "accel/build_ref.h"
#include "core/mesh.h"

namespace wideray {

class TriangleSplitter {
public:
    explicit TriangleSplitter(const TriangleMesh& mesh) : mesh_(mesh) {}

    /// `left` and `right` bound the parts of triangle `prim` inside `box` below and above the plane
    /// x[axis] = position (an empty box for a side without any). Conservative: a crossing point's
    /// rounding is covered by a few ulps of slack, so the two boxes hold every point of the part.
    void split(uint32_t prim, const BuildBox& box, int axis, float position, BuildBox& left, BuildBox& right) const;

private:
    const TriangleMesh& mesh_;
};

} // namespace wideray
