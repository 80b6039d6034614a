#include "backends/backend_registry.h"

#include "backends/accel_registry.h"
#include "backends/embree_structure.h"
#include "backends/find_by_name.h"

namespace wideray {
namespace {

constexpr Backend kBackends[] = {
    {"wideray", "our kernels over our structures (--accel: wide BVH by default)", &buildWideray},
    {"embree", "Intel Embree 3 (the yardstick)", &buildEmbree},
};

} // namespace

std::span<const Backend> backends() { return kBackends; }

const Backend& findBackend(std::string_view name) { return findByName(backends(), name, "--backend", "backend"); }

} // namespace wideray
