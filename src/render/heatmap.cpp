#include "render/heatmap.h"

#include <algorithm>
#include <array>

namespace wideray {

glm::vec3 heatmapColor(float x) {
    static const std::array<glm::vec3, 6> stops = {glm::vec3(0.19f, 0.07f, 0.23f), glm::vec3(0.27f, 0.47f, 0.96f),
                                                   glm::vec3(0.11f, 0.87f, 0.69f), glm::vec3(0.64f, 0.99f, 0.24f),
                                                   glm::vec3(0.98f, 0.73f, 0.22f), glm::vec3(0.48f, 0.02f, 0.01f)};
    float s = std::clamp(x, 0.0f, 1.0f) * float(stops.size() - 1);
    int i = std::min(int(s), int(stops.size()) - 2);
    return glm::mix(stops[i], stops[i + 1], s - float(i));
}

} // namespace wideray
