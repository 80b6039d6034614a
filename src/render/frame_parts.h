#pragma once
// A frame rendered in parts: its tiles, in Hilbert order, cut into runs that are rendered apart (by
// the ranks of an MPI job, src/mpi/) and joined into the image a single process renders, bit for bit:
// a pixel's samples and seeds depend on the pixel alone, and the tiles are the same.
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "backends/tracer.h"
#include "core/image.h"
#include "core/scene.h"
#include "render/film.h"
#include "render/render_options.h"
#include "render/tile_order.h"

namespace wideray {

/// One unit of work of a batch: part `part` of the `parts` parts of job `job`'s frame (parts = 1:
/// the whole frame).
struct WorkItem {
    uint32_t job = 0, part = 0, parts = 1;
};

/// Part `part` of `parts` of `tiles`: consecutive runs of nearly equal length; empty where there are
/// more parts than tiles.
std::span<const TileRect> partTiles(std::span<const TileRect> tiles, uint32_t part, uint32_t parts);

/// A rendered part: the frame it belongs to, the part's film values, and what the report says.
struct FramePart {
    WorkItem item;
    int width = 0, height = 0, tileSize = 0, samplesPerPixel = 0;
    Aov aov = Aov::Color;
    FilmTiles film;
    uint64_t triangles = 0;
    std::string accelName, engine;  ///< "BVH8", and the tracer's description
    double buildSeconds = 0;        ///< building the structure, where this part's rank built it for this part
};

/// Renders part `item` of the frame `scene` describes (its camera), through `tracer`; `options`
/// as for render(). The report fields (triangles, names, build time) are left to the caller.
FramePart renderPart(const SceneDescription& scene, const Tracer& tracer, const RenderOptions& options, const WorkItem& item);

/// Joins the parts of one frame as they arrive, in any order.
class FrameAssembler {
public:
    /// Takes a part in; true once every part of the frame is in. Throws std::runtime_error for a part
    /// that does not fit the frame the first part described (another size, tile size or AOV, or a
    /// part that is already in).
    bool add(FramePart&& part);

    /// The frame as render() returns it, once complete; the ray counts and the largest cost go to
    /// `stats`.
    Image finish(RenderStats& stats);

    /// The first part's description (size, samples, triangles, names), without its film values.
    const FramePart& description() const { return first_; }
    /// The longest build any part reported.
    double slowestBuild() const { return slowestBuild_; }

private:
    FramePart first_;
    std::unique_ptr<TileOrder> order_;
    std::unique_ptr<Film> film_;
    std::vector<bool> arrived_;
    uint32_t count_ = 0;
    double slowestBuild_ = 0;
};

} // namespace wideray
