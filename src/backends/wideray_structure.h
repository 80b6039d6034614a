#pragma once
// Our structure as a backend: the scene's N-wide BVH (accel/scene_accel.h), traced by the kernels
// of the registry (kernels/kernel_registry.h) for the ISA chosen.
#include <memory>

#include "accel/scene_accel.h"
#include "backends/structure.h"
#include "backends/backend_registry.h"

namespace wideray {

template <int N>
class WideBvhStructure final : public Structure {
public:
    explicit WideBvhStructure(std::shared_ptr<const SceneGeometry> geometry, BuildQuality quality = BuildQuality::Fast);

    const SceneAccel<N>& accel() const { return accel_; }
    std::string name() const override { return "BVH" + std::to_string(N); }
    BuildQuality quality() const { return quality_; }
    const char* qualityName() const { return quality_ == BuildQuality::High ? "high" : "fast"; }
    double buildSeconds() const override { return accel_.timings().totalSeconds(); }
    size_t bytes() const override { return accel_.bytes(); }
    std::string summary() const override;
    /// kernel "auto": packet256 for camera rays, the widest K-wide packets for their shadow rays,
    /// single for incoherent rays.
    std::unique_ptr<Tracer> tracer(const KernelChoice& choice) const override;

private:
    /// Memory of two-level instances against the flattened form; empty without instances.
    std::string instancingSummary() const;

    BuildQuality quality_;
    SceneAccel<N> accel_;
};

/// The ISA a choice asks for, checked against this CPU; throws InputError.
Isa chosenIsa(const KernelChoice& choice);

/// The bvh4, bvh8 and bvh16 rows' build function: the BVH of options.bvhWidth, fast or high quality.
std::shared_ptr<const Structure> buildWideBvh(std::shared_ptr<const SceneGeometry> geometry,
                                              const StructureOptions& options);

} // namespace wideray
