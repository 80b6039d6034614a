#include "accel/grid_build.h"

#include <algorithm>
#include <cmath>

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

#include "accel/triangle_box_overlap.h"

namespace wideray {

// The parameters, measured on the shared meshes (docs/accelerators.md).
GridConfig uniformGridConfig() {
    // Measured on Sponza from inside and the bunny framed, lambda = 1 to 32: Sponza's camera rays
    // 0.61, 0.79, 0.94, 1.00, 1.06, 0.92 Mrays/s, the bunny's 2.41, 2.27, 2.40, 2.29, 1.97, 1.64:
    // lambda = 8 is near the best of both (docs/accelerators.md).
    GridConfig c;
    c.density = 8.0f;
    return c;
}

GridConfig hierarchicalGridConfig() {
    GridConfig c;
    c.refineAbove = 16;
    c.maxLevels = 2;
    return c;
}

GridConfig recursiveGridConfig() {
    GridConfig c;
    c.density = 1.0f / 16.0f;
    c.refineAbove = 8;
    c.subDensity = 1.0f;
    c.maxLevels = 5;
    return c;
}

namespace {

struct CellItem {
    uint32_t cell, item;
    bool operator<(const CellItem& o) const { return cell != o.cell ? cell < o.cell : item < o.item; }
};

class GridBuilder {
public:
    GridBuilder(const PrimitiveTable& table, const GridConfig& config, Grid& out)
        : table_(table), config_(config), out_(out) {}

    /// Builds a grid over `box` holding `items`, and the finer grids in its crowded cells; returns its
    /// index in out.grids.
    uint32_t build(Bounds3f box, const std::vector<uint32_t>& items, int level) {
        const GridLevel g = layout(box, level == 0 ? config_.density : config_.subDensity, items.size());
        const uint32_t index = uint32_t(out_.grids.size());
        out_.grids.push_back(g);
        const uint32_t cellCount = uint32_t(g.res[0]) * uint32_t(g.res[1]) * uint32_t(g.res[2]);
        out_.cells.resize(size_t(g.firstCell) + cellCount, GridCell{0, 0});
        const std::vector<CellItem> binned = bin(g, items);
        std::vector<uint32_t> cellItems;
        for (size_t i = 0; i < binned.size();) {
            const uint32_t cell = binned[i].cell;
            cellItems.clear();
            for (; i < binned.size() && binned[i].cell == cell; ++i) cellItems.push_back(binned[i].item);
            GridCell result{uint32_t(out_.items.size()), uint32_t(cellItems.size())};
            if (level + 1 < config_.maxLevels && config_.refineAbove && cellItems.size() > config_.refineAbove) {
                if (const uint32_t sub = refine(g, cell, cellItems, level); sub != 0) result = {sub, GridCell::kSubgridFlag};
            }
            if (!result.isSubgrid()) out_.items.insert(out_.items.end(), cellItems.begin(), cellItems.end());
            out_.cells[g.firstCell + cell] = result;
        }
        return index;
    }

private:
    GridLevel layout(Bounds3f box, float density, size_t itemCount) const {
        // Flat boxes get a thickness, so that every cell has a volume and every side a reciprocal.
        glm::vec3 e = box.extent();
        const float largest = std::max({e.x, e.y, e.z, 1e-20f});
        for (int a = 0; a < 3; ++a)
            if (e[a] < largest * 0x1p-10f) {
                // Large enough not to round away at the box's coordinates.
                const float magnitude = std::max(std::fabs(box.lower[a]), std::fabs(box.upper[a]));
                const float pad = std::max({largest * 0x1p-11f, magnitude * 0x1p-20f, 1e-30f});
                box.lower[a] -= pad;
                box.upper[a] += pad;
            }
        e = box.extent();
        // res[a] = e[a] * k with k^3 * volume = cells; axes too short for one cell at that k get one
        // cell, and k is solved again over the rest.
        const double cells = std::max(1.0, double(density) * double(itemCount));
        bool single[3] = {false, false, false};
        double k = 0;
        for (int pass = 0; pass < 3; ++pass) {
            double volume = 1, axes = 0;
            for (int a = 0; a < 3; ++a)
                if (!single[a]) volume *= double(e[a]), ++axes;
            if (axes == 0) break;
            k = std::pow(cells / volume, 1.0 / axes);
            bool changed = false;
            for (int a = 0; a < 3; ++a)
                if (!single[a] && !(double(e[a]) * k >= 1.0)) single[a] = changed = true;  // NaN too
            if (!changed) break;
        }
        GridLevel g{};
        for (int a = 0; a < 3; ++a) {
            const double r = std::round(double(e[a]) * k);
            g.res[a] = single[a] || !(r >= 1.0) ? 1 : (r >= double(config_.maxResolution) ? config_.maxResolution : int(r));
            g.lower[a] = box.lower[a];
            g.upper[a] = box.upper[a];
            g.cellSize[a] = e[a] / float(g.res[a]);
            g.invCellSize[a] = float(g.res[a]) / e[a];
        }
        g.firstCell = uint32_t(out_.cells.size());
        return g;
    }

    /// Every (cell, item) pair where the item touches the cell grown by the margin, sorted by cell.
    std::vector<CellItem> bin(const GridLevel& g, const std::vector<uint32_t>& items) const {
        // The margin covers the walk's rounding (its entry cell and boundary distances): a fraction of
        // a cell, and more than the ulps of the coordinates.
        glm::vec3 margin;
        for (int a = 0; a < 3; ++a)
            margin[a] = g.cellSize[a] * 0x1p-10f + std::max(std::fabs(g.lower[a]), std::fabs(g.upper[a])) * 0x1p-20f;
        auto cellRange = [&](const Bounds3f& b, glm::ivec3& lo, glm::ivec3& hi) {
            for (int a = 0; a < 3; ++a) {
                const auto index = [&](float x) {
                    const double f = std::floor(double(x - g.lower[a]) * g.invCellSize[a]);
                    return !(f >= 0.0) ? 0 : (f >= double(g.res[a]) ? g.res[a] - 1 : int(f));
                };
                lo[a] = index(b.lower[a] - margin[a]);
                hi[a] = index(b.upper[a] + margin[a]);
            }
        };
        auto forEachCell = [&](uint32_t item, auto&& visit) {
            const Bounds3f& b = table_.box(item);
            for (int a = 0; a < 3; ++a)
                if (b.upper[a] + margin[a] < g.lower[a] || b.lower[a] - margin[a] > g.upper[a]) return;
            glm::ivec3 lo, hi;
            cellRange(b, lo, hi);
            // A triangle whose box lies in one cell touches it; only a box across cells needs the test.
            const bool triangle = table_.isTriangle(item) && lo != hi;
            const TriangleVertices* t = triangle ? &table_.vertices(item) : nullptr;
            for (int z = lo.z; z <= hi.z; ++z)
                for (int y = lo.y; y <= hi.y; ++y)
                    for (int x = lo.x; x <= hi.x; ++x) {
                        const glm::ivec3 c(x, y, z);
                        if (triangle) {
                            glm::dvec3 cl, cu;
                            for (int a = 0; a < 3; ++a) {
                                cl[a] = double(g.lower[a]) + double(c[a]) * double(g.cellSize[a]) - margin[a];
                                cu[a] = double(g.lower[a]) + double(c[a] + 1) * double(g.cellSize[a]) + margin[a];
                            }
                            if (!triangleOverlapsBox(cl, cu, {t->v0x, t->v0y, t->v0z}, {t->v1x, t->v1y, t->v1z},
                                                     {t->v2x, t->v2y, t->v2z}))
                                continue;
                        }
                        visit(uint32_t((z * g.res[1] + y) * g.res[0] + x));
                    }
        };
        // One pass of overlap tests, into each thread's list; the sort makes the order deterministic.
        tbb::enumerable_thread_specific<std::vector<CellItem>> found;
        tbb::parallel_for(tbb::blocked_range<size_t>(0, items.size(), 1024), [&](const tbb::blocked_range<size_t>& r) {
            std::vector<CellItem>& out = found.local();
            for (size_t i = r.begin(); i != r.end(); ++i)
                forEachCell(items[i], [&](uint32_t cell) { out.push_back({cell, items[i]}); });
        });
        std::vector<CellItem> pairs;
        for (const std::vector<CellItem>& part : found) pairs.insert(pairs.end(), part.begin(), part.end());
        tbb::parallel_sort(pairs.begin(), pairs.end());
        return pairs;
    }

    /// A finer grid in a crowded cell; 0 (and nothing kept) where it would not thin the cell out.
    uint32_t refine(const GridLevel& g, uint32_t cell, const std::vector<uint32_t>& items, int level) {
        const uint32_t x = cell % uint32_t(g.res[0]), y = (cell / uint32_t(g.res[0])) % uint32_t(g.res[1]),
                       z = cell / (uint32_t(g.res[0]) * uint32_t(g.res[1]));
        const glm::uvec3 c(x, y, z);
        Bounds3f box;
        for (int a = 0; a < 3; ++a) {
            box.lower[a] = g.lower[a] + float(c[a]) * g.cellSize[a];
            box.upper[a] = c[a] + 1 == uint32_t(g.res[a]) ? g.upper[a] : g.lower[a] + float(c[a] + 1) * g.cellSize[a];
        }
        const size_t grids = out_.grids.size(), cells = out_.cells.size(), stored = out_.items.size();
        const uint32_t sub = build(box, items, level + 1);
        // Items that span the whole cell would fill every finer cell too: then the cell stays as it is.
        size_t full = 0, references = out_.items.size() - stored;
        for (size_t i = cells; i < out_.cells.size(); ++i) full += out_.cells[i].count ? 1 : 0;
        if (full == 0 || double(references) / double(full) <= 0.75 * double(items.size())) return sub;
        out_.grids.resize(grids);
        out_.cells.resize(cells);
        out_.items.resize(stored);
        return 0;
    }

    const PrimitiveTable& table_;
    const GridConfig& config_;
    Grid& out_;
};

} // namespace

Grid buildGrid(const PrimitiveTable& table, const GridConfig& config) {
    Grid out;
    if (table.size() == 0) return out;
    std::vector<uint32_t> items(table.size());
    for (uint32_t i = 0; i < table.size(); ++i) items[i] = i;
    GridBuilder(table, config, out).build(table.bounds(), items, 0);
    for (const GridCell& c : out.cells) out.emptyCells += c.count == 0 ? 1 : 0;
    // Finer grids come after the grid that holds them.
    std::vector<int> level(out.grids.size(), 1);
    for (size_t g = 0; g < out.grids.size(); ++g) {
        out.levels = std::max(out.levels, level[g]);
        const GridLevel& grid = out.grids[g];
        const size_t cells = size_t(grid.res[0]) * size_t(grid.res[1]) * size_t(grid.res[2]);
        for (size_t c = grid.firstCell; c < grid.firstCell + cells; ++c)
            if (out.cells[c].isSubgrid()) level[out.cells[c].first] = level[g] + 1;
    }
    return out;
}

} // namespace wideray
