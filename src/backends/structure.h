#pragma once
// An acceleration structure of a scene's geometry, built once: our wide BVH, an Embree scene at a
// build quality; later kd-trees and grids. It reports its build time and size and makes tracers,
// cheap objects over it and a choice of kernels, as many as a benchmark wants.
#include <memory>
#include <optional>
#include <string>

#include "backends/tracer.h"
#include "geometry/scene_geometry.h"
#include "simd/cpu_features.h"

namespace wideray {

/// The kernels a tracer runs: a kernel of the structure's backend by name, or "auto" for the
/// backend's own choice per kind of ray.
struct KernelChoice {
    KernelChoice() = default;
    KernelChoice(std::string name, std::optional<Isa> chosenIsa = std::nullopt, bool cache = false)
        : kernel(std::move(name)), isa(chosenIsa), shadowCache(cache) {}

    std::string kernel = "auto";
    std::optional<Isa> isa;    ///< our kernels: nullopt is the best this CPU has
    bool shadowCache = false;  ///< our kernels: last-occluder cache for incoherent shadow rays
};

class Structure : public std::enable_shared_from_this<Structure> {
public:
    explicit Structure(std::shared_ptr<const SceneGeometry> geometry) : geometry_(std::move(geometry)) {}
    virtual ~Structure() = default;

    const SceneGeometry& geometry() const { return *geometry_; }

    /// What the build is called in reports ("BVH8", "Embree BVH").
    virtual std::string name() const = 0;
    virtual double buildSeconds() const = 0;
    virtual size_t bytes() const = 0;
    /// The structure's shape in one line or more, for `wideray info`.
    virtual std::string summary() const = 0;
    /// Throws InputError when the choice names a kernel the backend lacks or the CPU cannot run.
    virtual std::unique_ptr<Tracer> tracer(const KernelChoice& choice) const = 0;

private:
    std::shared_ptr<const SceneGeometry> geometry_;
};

} // namespace wideray
