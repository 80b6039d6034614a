#pragma once
// Embree's entry points behind our Tracer interface, over an EmbreeStructure.
#include <memory>
#include <optional>
#include <string_view>

#include "backends/embree_structure.h"

namespace wideray {

/// Which Embree entry point traces a batch: one ray at a time, SoA packets of K, or a ray stream.
enum class EmbreeKernel { Intersect1, Packet4, Packet8, Packet16, Stream1M };

/// The entry point's name, e.g. "rtcIntersect16" ("rtcOccluded16" for the same kernel's shadow rays).
const char* embreeKernelName(EmbreeKernel kernel);
std::optional<EmbreeKernel> parseEmbreeKernel(std::string_view name);
/// Whether this CPU and Embree build run the kernel (packets natively, streams at all).
bool embreeSupports(EmbreeKernel kernel);
/// The widest packet this CPU and Embree build run natively.
EmbreeKernel widestNativeEmbreePacket();

class EmbreeTracer final : public Tracer {
public:
    /// Throws InputError when this Embree build or CPU cannot run one of the kernels natively.
    EmbreeTracer(std::shared_ptr<const EmbreeStructure> structure, EmbreeKernel coherent, EmbreeKernel incoherent);

    /// Embree reports no traversal work: `costs`, when given, is filled with zeros.
    void intersect(std::span<const Ray> rays, std::span<Hit> hits, Coherence coherence,
                   TraversalCost* costs = nullptr) const override;
    /// Embree keeps no per-depth state: `depth` is ignored.
    void occluded(std::span<const Ray> rays, std::span<uint8_t> occluded, Coherence coherence,
                  int depth = -1) const override;
    const SceneGeometry& geometry() const override { return structure_->geometry(); }
    std::string description() const override;

private:
    EmbreeKernel kernel(Coherence c) const { return c == Coherence::Coherent ? coherent_ : incoherent_; }

    std::shared_ptr<const EmbreeStructure> structure_;
    EmbreeKernel coherent_, incoherent_;
};

} // namespace wideray
