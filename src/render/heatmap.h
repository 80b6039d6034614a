#pragma once
// A perceptual color map for cost images.
#include <glm/glm.hpp>

namespace wideray {

/// Maps x in [0, 1] to a color from dark blue through green and yellow to red (Turbo-like, built as
/// a piecewise-linear ramp through fixed stops).
glm::vec3 heatmapColor(float x);

} // namespace wideray
