#pragma once
// Where a ray's line crosses the boundary of a closed solid: what CSG (geometry/csg_geometry.h) works
// from. A solid lists its crossings in increasing t, each one a change of the line between outside and
// inside, with the hit its geometry's surface() takes to shade the crossing.
#include <cstdint>
#include <vector>

namespace wideray {

struct SolidCrossing {
    double t;
    bool enters;       ///< the line goes from outside the solid to inside
    uint32_t primId;   ///< the primitive crossed, and u, v as its geometry's intersect() writes them
    float u = 0.0f, v = 0.0f;
    uint32_t leaf = 0; ///< CSG: which solid of the tree
};

using SolidCrossings = std::vector<SolidCrossing>;

} // namespace wideray
