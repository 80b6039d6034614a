#include "backends/backend_registry.h"

#include "backends/accel_registry.h"
#include "backends/embree_structure.h"
#include "core/error.h"

namespace wideray {
namespace {

constexpr Backend kBackends[] = {
    {"wideray", "our kernels over our structures (--accel: wide BVH by default)", &buildWideray},
    {"embree", "Intel Embree 3 (the yardstick)", &buildEmbree},
};

} // namespace

std::span<const Backend> backends() { return kBackends; }

const Backend& findBackend(std::string_view name) {
    std::string names;
    for (const Backend& b : kBackends) {
        if (name == b.name) return b;
        names += std::string(names.empty() ? "" : ", ") + b.name;
    }
    throw InputError("--backend", "", "no backend is named '" + std::string(name) + "' (expected " + names + ")");
}

} // namespace wideray
