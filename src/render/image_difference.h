#pragma once
// How much two renders of the same scene differ (our kernels against Embree, say).
#include <cstddef>

#include "core/image.h"

namespace wideray {

struct ImageDifference {
    double meanAbsolute = 0;  ///< over all channel values
    double maxAbsolute = 0;
    size_t pixelsOver = 0;    ///< pixels with any channel differing by more than the threshold
    size_t pixels = 0;
};

/// Both images must have the same size and channels.
ImageDifference compareImages(const Image& a, const Image& b, float threshold);

} // namespace wideray
