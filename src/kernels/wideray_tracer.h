#pragma once
// Our tracer: the scene's wide BVH traced by the kernels chosen for coherent and incoherent rays.
#include <memory>

#include "core/scene_accel.h"
#include "core/tracer.h"
#include "kernels/kernel_set.h"

namespace wideray {

template <int N>
class WiderayTracer final : public Tracer {
public:
    WiderayTracer(std::shared_ptr<const SceneAccel<N>> accel, KernelSet<N> coherent, KernelSet<N> incoherent)
        : accel_(std::move(accel)), view_(accel_->view()), coherent_(coherent), incoherent_(incoherent) {}

    void intersect(std::span<const Ray> rays, std::span<Hit> hits, Coherence coherence,
                   TraversalCost* costs) const override {
        kernel(coherence).intersect(view_, rays.data(), hits.data(), rays.size(), costs);
    }
    void occluded(std::span<const Ray> rays, std::span<uint8_t> occluded, Coherence coherence) const override {
        kernel(coherence).occluded(view_, rays.data(), occluded.data(), rays.size());
    }
    const Geometry& geometry(uint32_t geomId) const override { return accel_->geometry(geomId); }
    std::string description() const override {
        return std::string("wideray BVH") + std::to_string(N) + " " + coherent_.name + "/" + incoherent_.name;
    }

private:
    const KernelSet<N>& kernel(Coherence c) const { return c == Coherence::Coherent ? coherent_ : incoherent_; }

    std::shared_ptr<const SceneAccel<N>> accel_;
    SceneView<N> view_;
    KernelSet<N> coherent_, incoherent_;
};

} // namespace wideray
