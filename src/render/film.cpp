#include "render/film.h"

#include <algorithm>

#include "render/heatmap.h"

namespace wideray {

Film::Film(int width, int height, Aov aov, int samplesPerPixel)
    : aov_(aov), sampleWeight_(1.0f / float(samplesPerPixel)), image_(width, height, aov == Aov::Depth ? 1 : 3),
      cost_(aov == Aov::Cost ? size_t(width) * size_t(height) : 0) {}

Image Film::finish(RenderStats& stats) {
    stats.primaryRays = primaryRays_;
    stats.secondaryRays = secondaryRays_;
    stats.shadowRays = shadowRays_;
    if (aov_ == Aov::Cost) {
        uint32_t maxCost = 1;
        for (uint32_t c : cost_) maxCost = std::max(maxCost, c);
        stats.maxCost = maxCost;
        for (size_t p = 0; p < cost_.size(); ++p) {
            glm::vec3 c = heatmapColor(float(cost_[p]) / float(maxCost));
            for (int k = 0; k < 3; ++k) image_.pixels[p * 3 + k] = c[k];
        }
    }
    return std::move(image_);
}

} // namespace wideray
