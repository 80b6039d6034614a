#pragma once
// The backends, one row each: who builds structures and traces rays. render, info and bench choose
// from this list by name.
#include <memory>
#include <span>
#include <string>
#include <string_view>

#include "backends/structure.h"

namespace wideray {

struct StructureOptions {
    /// wideray: the structure (backends/accel_registry.h); empty: the wide BVH of bvhWidth
    std::string accel;
    int bvhWidth = 8;  ///< wideray: children per node, 4, 8 or 16
    /// wideray: fast (object splits) or high (spatial splits too); embree: low, medium or high
    /// (RTC_BUILD_QUALITY_*), fast meaning medium. Empty: the backend's default (fast, medium).
    std::string quality;
};

struct Backend {
    const char* name;
    const char* description;
    /// Throws InputError for options the backend cannot build.
    std::shared_ptr<const Structure> (*build)(std::shared_ptr<const SceneGeometry> geometry,
                                              const StructureOptions& options);
};

std::span<const Backend> backends();
/// The backend named `name`; throws InputError (naming the valid ones) otherwise.
const Backend& findBackend(std::string_view name);

} // namespace wideray
