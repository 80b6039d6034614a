#pragma once
// Grids walked cell by cell along the ray with the 3D-DDA of Amanatides and Woo (1987, "A fast voxel
// traversal algorithm for ray tracing"); a cell holding a finer grid is walked the same way over the
// ray's part inside it (hierarchical and recursive grids). Primitives listed in several cells are
// tested once per ray (the mailbox).
#include <cmath>

#include "kernels/traverse_bvh2.h"

#include "simd/isa_namespace.h"

namespace wideray {
inline namespace WIDERAY_ISA {

/// The closest hit found so far ends the walk only when it lies before the cell's exit by this much
/// (relative), which covers the rounding of both distances.
constexpr float kGridExitSlack = 0x1p-16f;

struct GridRay {
    const Ray& ray;
    const SingleRayState& s;
    float origin[3], dir[3], rdir[3];
};

/// Walks grid `level` over the ray's part [t0, t1] inside it; returns true when the walk is over
/// (any-hit: occluded; closest-hit: the hit lies before everything left).
template <bool AnyHit>
inline bool walkGrid(const GridView& grid, uint32_t level, const GridRay& r, float t0, float t1, Hit& hit,
                     Mailbox& mailbox, TraversalCost& cost) {
    const GridLevel& g = grid.grids[level];
    int cell[3], step[3], last[3];
    float tNext[3];
    for (int a = 0; a < 3; ++a) {
        // The cell of the entry point; rounding may put it one cell off near a boundary, which the
        // builder's margin around every cell covers.
        // In double: far from the grid a float position would be off by more than the margin.
        const float p = float(double(r.origin[a]) + double(t0) * double(r.dir[a]));
        const float f = std::floor((p - g.lower[a]) * g.invCellSize[a]);
        const int c = !(f >= 0.0f) ? 0 : (f >= float(g.res[a]) ? g.res[a] - 1 : int(f));  // clamped before converting
        cell[a] = c;
        if (std::signbit(r.rdir[a])) {
            step[a] = -1;
            last[a] = -1;
            tNext[a] = (g.lower[a] + float(c) * g.cellSize[a] - r.origin[a]) * r.rdir[a];
        } else {
            step[a] = 1;
            last[a] = g.res[a];
            tNext[a] = (g.lower[a] + float(c + 1) * g.cellSize[a] - r.origin[a]) * r.rdir[a];
        }
        if (tNext[a] != tNext[a]) tNext[a] = __builtin_huge_valf();  // in a boundary plane, parallel to it
    }
    float tEnter = t0;
    for (;;) {
        const int axis = tNext[0] < tNext[1] ? (tNext[0] < tNext[2] ? 0 : 2) : (tNext[1] < tNext[2] ? 1 : 2);
        const float tExit = tNext[axis] < t1 ? tNext[axis] : t1;
        ++cost.nodes;
        const GridCell c = grid.cells[g.firstCell + (uint32_t(cell[2]) * uint32_t(g.res[1]) + uint32_t(cell[1])) *
                                                        uint32_t(g.res[0]) + uint32_t(cell[0])];
        if (c.isSubgrid()) {
            if (walkGrid<AnyHit>(grid, c.first, r, tEnter, tExit, hit, mailbox, cost)) return true;
        } else if (c.count && intersectItems<AnyHit>(grid.prims, grid.items + c.first, c.count, r.s, r.ray, hit,
                                                      &mailbox, cost)) {
            return true;
        }
        if (!AnyHit && hit.t < tExit - std::fabs(tExit) * kGridExitSlack) return true;
        if (tNext[axis] >= t1) return false;
        cell[axis] += step[axis];
        if (cell[axis] == last[axis]) return false;
        const int boundary = cell[axis] + (step[axis] > 0 ? 1 : 0);
        tNext[axis] = (g.lower[axis] + float(boundary) * g.cellSize[axis] - r.origin[axis]) * r.rdir[axis];
        tEnter = tExit;
    }
}

template <bool AnyHit>
inline bool traceGrid(const GridView& grid, const Ray& ray, Hit& hit, TraversalCost& cost) {
    if (!grid.grids || !isValidRay(ray)) return false;
    const SingleRayState s = makeSingleRayState(ray);
    const GridLevel& top = grid.grids[0];
    const BoxPlanes box{{top.lower[0], top.upper[0], top.lower[1], top.upper[1], top.lower[2], top.upper[2]}};
    float t0, t1;
    if (!intersectBox(box, s.box, ray.tnear, ray.tfar, t0, t1)) return false;
    const GridRay r{ray, s, {ray.ox, ray.oy, ray.oz}, {ray.dx, ray.dy, ray.dz}, {s.box.slab.rdx, s.box.slab.rdy, s.box.slab.rdz}};
    Mailbox mailbox;
    return walkGrid<AnyHit>(grid, 0, r, t0, t1, hit, mailbox, cost) && AnyHit;
}

} // namespace WIDERAY_ISA
} // namespace wideray
