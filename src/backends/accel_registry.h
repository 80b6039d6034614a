#pragma once
// Our acceleration structures, one row each: the wide BVHs every kernel traverses, and the course's
// structures (binary and skip-pointer BVHs, kd-tree, grids) traced one ray at a time. render, info
// and bench choose among them with --accel.
#include <memory>
#include <span>
#include <string_view>

#include "backends/backend_registry.h"

namespace wideray {

struct Accel {
    const char* name;
    const char* description;
    std::shared_ptr<const Structure> (*build)(std::shared_ptr<const SceneGeometry> geometry,
                                              const StructureOptions& options);
    bool wideBvh = false;  ///< one of our wide BVHs (every kernel, two build qualities, two-level instances)
};

std::span<const Accel> accels();
/// The structure named `name`; throws InputError (naming the valid ones) otherwise.
const Accel& findAccel(std::string_view name);
/// Whether `name` is one of our wide BVHs rather than one of the course's structures.
bool isWideBvh(std::string_view name);

/// The wideray backend's build function: options.accel, or the wide BVH of options.bvhWidth.
std::shared_ptr<const Structure> buildWideray(std::shared_ptr<const SceneGeometry> geometry,
                                              const StructureOptions& options);

} // namespace wideray
