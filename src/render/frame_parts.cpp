#include "render/frame_parts.h"

#include <stdexcept>

#include "render/render_memory.h"
#include "render/renderer.h"

namespace wideray {

std::span<const TileRect> partTiles(std::span<const TileRect> tiles, uint32_t part, uint32_t parts) {
    const uint64_t n = tiles.size();
    const size_t begin = size_t(n * part / parts), end = size_t(n * (part + 1) / parts);
    return tiles.subspan(begin, end - begin);
}

FramePart renderPart(const SceneDescription& scene, const Tracer& tracer, const RenderOptions& options, const WorkItem& item) {
    const RenderOptions resolved = resolveRenderOptions(scene, options);
    checkRenderFits(resolved, options.label.empty() ? scene.file.string() : options.label);
    const TileOrder order(resolved.width, resolved.height, resolved.tileSize);
    const std::span<const TileRect> tiles = partTiles(order.tiles(), item.part, item.parts);
    Film film(resolved.width, resolved.height, resolved.aov, resolved.samplesPerPixel);
    FramePart part;
    part.item = item;
    part.width = resolved.width;
    part.height = resolved.height;
    part.tileSize = resolved.tileSize;
    part.samplesPerPixel = resolved.samplesPerPixel;
    part.aov = resolved.aov;
    renderTiles(scene, tracer, resolved, order, tiles, film);
    part.film = film.extract(tiles);
    return part;
}

bool FrameAssembler::add(FramePart&& part) {
    if (!film_) {
        if (part.item.parts == 0 || part.width <= 0 || part.height <= 0 || part.tileSize <= 0 ||
            part.samplesPerPixel <= 0)
            throw std::runtime_error("a frame part without a valid frame description");
        order_ = std::make_unique<TileOrder>(part.width, part.height, part.tileSize);
        film_ = std::make_unique<Film>(part.width, part.height, part.aov, part.samplesPerPixel);
        arrived_.assign(part.item.parts, false);
        FilmTiles film = std::move(part.film);
        first_ = part;  // the description alone
        part.film = std::move(film);
    }
    const WorkItem& item = part.item;
    if (item.job != first_.item.job || item.parts != first_.item.parts || item.part >= item.parts ||
        part.width != first_.width || part.height != first_.height || part.tileSize != first_.tileSize ||
        part.aov != first_.aov || part.samplesPerPixel != first_.samplesPerPixel)
        throw std::runtime_error("frame part " + std::to_string(item.part) + " of " + std::to_string(item.parts) +
                                 " does not fit its frame");
    if (arrived_[item.part]) throw std::runtime_error("frame part " + std::to_string(item.part) + " arrived twice");
    film_->insert(partTiles(order_->tiles(), item.part, item.parts), part.film);
    arrived_[item.part] = true;
    slowestBuild_ = std::max(slowestBuild_, part.buildSeconds);
    return ++count_ == first_.item.parts;
}

Image FrameAssembler::finish(RenderStats& stats) {
    if (!film_ || count_ != first_.item.parts) throw std::logic_error("FrameAssembler::finish before every part is in");
    return film_->finish(stats);
}

} // namespace wideray
