#pragma once
// A float image: renders, AOVs and image textures.
#include <vector>

namespace wideray {

struct Image {
    int width = 0, height = 0, channels = 3;
    std::vector<float> pixels;  ///< row-major, channels interleaved, linear values

    Image() = default;
    Image(int w, int h, int c) : width(w), height(h), channels(c), pixels(size_t(w) * h * c, 0.0f) {}
    float* at(int x, int y) { return &pixels[(size_t(y) * width + x) * channels]; }
    const float* at(int x, int y) const { return &pixels[(size_t(y) * width + x) * channels]; }
};

} // namespace wideray
