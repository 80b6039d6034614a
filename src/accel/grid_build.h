#pragma once
// Uniform, hierarchical and recursive grids over a PrimitiveTable's items. The uniform grid has about
// density * N cells, sides in proportion to the scene's (Klimaszewski and Sederberg 1997, "Faster ray
// tracing using adaptive grids"); items are binned into every cell their triangle touches (exact
// triangle-box overlap), with a margin around each cell that covers the walk's rounding. A
// hierarchical grid gives each crowded cell of the uniform grid a finer grid of its own, once; a
// recursive grid starts coarse and refines crowded cells again and again (Jevans and Wyvill 1989,
// "Adaptive voxel subdivision for ray tracing").
#include <cstddef>
#include <vector>

#include "accel/primitive_table.h"

namespace wideray {

struct GridConfig {
    /// Cells per item of the top grid (lambda).
    float density = 2.0f;
    /// Cells holding more items than this get a grid of their own (0: never).
    uint32_t refineAbove = 0;
    /// Cells per item of the finer grids.
    float subDensity = 2.0f;
    /// Grid levels at most, the top one included.
    int maxLevels = 1;
    int maxResolution = 1024;  ///< cells per side at most
};

/// The three grids of the course, as configured by `wideray --accel grid|hgrid|rgrid`.
GridConfig uniformGridConfig();
GridConfig hierarchicalGridConfig();
GridConfig recursiveGridConfig();

struct Grid {
    std::vector<GridLevel> grids;
    std::vector<GridCell> cells;
    std::vector<uint32_t> items;
    size_t emptyCells = 0;
    int levels = 0;
};

Grid buildGrid(const PrimitiveTable& table, const GridConfig& config);

} // namespace wideray
