#include "render/image_difference.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace wideray {

ImageDifference compareImages(const Image& a, const Image& b, float threshold) {
    if (a.width != b.width || a.height != b.height || a.channels != b.channels)
        throw std::invalid_argument("compareImages: the images differ in size or channels");
    ImageDifference d;
    d.pixels = size_t(a.width) * size_t(a.height);
    double sum = 0;
    for (size_t p = 0; p < d.pixels; ++p) {
        bool over = false;
        for (int c = 0; c < a.channels; ++c) {
            double diff = std::fabs(double(a.pixels[p * a.channels + c]) - double(b.pixels[p * a.channels + c]));
            sum += diff;
            d.maxAbsolute = std::max(d.maxAbsolute, diff);
            over = over || diff > threshold;
        }
        d.pixelsOver += over;
    }
    d.meanAbsolute = a.pixels.empty() ? 0.0 : sum / double(a.pixels.size());
    return d;
}

} // namespace wideray
