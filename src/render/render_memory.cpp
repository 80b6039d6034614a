#include "render/render_memory.h"

#include <unistd.h>

#include <algorithm>

#include <fmt/core.h>

#include "core/error.h"

namespace wideray {

uint64_t renderBytes(const RenderOptions& options) {
    const uint64_t pixels = uint64_t(std::max(options.width, 0)) * uint64_t(std::max(options.height, 0));
    // Up to 2^62 pixels from two ints: saturate rather than wrap in the products below.
    if (pixels > UINT64_MAX / 64) return UINT64_MAX;
    const uint64_t channels = options.aov == Aov::Depth ? 1 : 3;
    const uint64_t film = pixels * channels * sizeof(float) + (options.aov == Aov::Cost ? pixels * sizeof(uint32_t) : 0);
    return 2 * film;  // the film and the image finished from it
}

uint64_t physicalMemoryBytes() {
    const long pages = sysconf(_SC_PHYS_PAGES), pageSize = sysconf(_SC_PAGE_SIZE);
    return pages > 0 && pageSize > 0 ? uint64_t(pages) * uint64_t(pageSize) : UINT64_MAX;
}

void checkRenderFits(const RenderOptions& options, const std::string& file, uint64_t available) {
    const uint64_t needed = renderBytes(options);
    if (needed <= available) return;
    constexpr double kGiB = 1024.0 * 1024.0 * 1024.0;
    throw InputError(file, "", fmt::format("{}x{} needs {:.1f} GiB for its film and image; this machine has {:.1f} GiB",
                                           options.width, options.height, double(needed) / kGiB, double(available) / kGiB));
}

} // namespace wideray
