#pragma once
// Renders for the tests: through the scalar reference, on a given number of threads.
#include <tbb/global_control.h>

#include "core/fp_mode.h"
#include "render/renderer.h"
#include "backends/wideray_structure.h"

namespace wideray {

inline Image renderWithReference(const SceneDescription& scene, int threads, const RenderOptions& options,
                                 RenderStats* statsOut = nullptr) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, size_t(threads));
    FlushToZeroScope ftz;
    std::unique_ptr<Tracer> tracer = buildWideBvh(std::make_shared<const SceneGeometry>(scene), {})->tracer({"scalar"});
    RenderStats stats;
    Image image = render(scene, *tracer, options, stats);
    if (statsOut) *statsOut = stats;
    return image;
}

} // namespace wideray
