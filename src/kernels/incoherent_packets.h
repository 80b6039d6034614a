#pragma once
// Which incoherent closest-hit packets part singly (traversePacket): those of a batch whose rays
// mostly hit, and those whose rays start far apart.
#include <algorithm>
#include <cstdint>

#include "accel/bvh_view.h"
#include "kernels/ray_state.h"

#include "simd/isa_namespace.h"

namespace wideray {
inline namespace WIDERAY_ISA {

/// How far the origins of a packet's rays spread, along the axis where they spread most; infinite for
/// a packet with invalid lanes (paths that ended, the short last packet of a batch), which so parts
/// singly as well: measured faster than keeping such packets whole by their valid rays' spread (the
/// bunny's bounce rays, `packet16`, 1.03x, ABBA 2 rounds; session 24).
template <int K>
inline float originSpread(const PacketRay<K>& p, const vbool<K>& valid) {
    if (!all(valid)) return __builtin_huge_valf();
    const vfloat<K>* o[3] = {&p.ox, &p.oy, &p.oz};
    float spread = 0.0f;
    for (int a = 0; a < 3; ++a) spread = std::max(spread, reduceMax(*o[a]) - reduceMin(*o[a]));
    return spread;
}

/// Ordering each ray's children its own way pays where most rays hit something, not where most
/// escape, which packet steps drop together (measured: rays from inside Sponza and the country
/// kitchen, packet16 0.6-0.9x of single rays before and 0.95-1.0x parting singly; diffuse rays off
/// framed Sponza, 97% escaping, 2.4x single rays in packets and 1.4x parting singly). So packets part
/// singly while four in five of the rays traced so far in the batch hit (recent packets weigh most:
/// the counts halve every 4096 rays). Escaping rays that start far apart share few nodes, though: a
/// packet step serves one or two of them, and each lane is dragged through the leaves the others
/// enter (bounce rays off the framed bunny, which start all over it: 14.5 leaves per ray in whole
/// packets, 2.3 as single rays, and 0.5x the single rays' speed). So packets whose origins spread
/// over more than kSpreadFraction of the scene's largest extent part singly too; the rays of
/// neighbouring pixels' diffuse bounces start close together and stay whole.
class IncoherentPackets {
public:
    template <int N>
    explicit IncoherentPackets(const SceneView<N>& scene)
        : spreadLimit_(scene.bounds.empty() ? __builtin_huge_valf()
                                            : kSpreadFraction * scene.bounds.extent()[scene.bounds.largestAxis()]) {}

    /// Whether a packet of the batch, `valid` its rays, parts singly.
    template <int K>
    bool partSingly(const PacketRay<K>& p, const vbool<K>& valid) const {
        return 5 * hits_ >= 4 * rays_ || originSpread(p, valid) > spreadLimit_;
    }

    void add(uint32_t rays, uint32_t hits) {
        rays_ += rays;
        hits_ += hits;
        if (rays_ >= 4096) rays_ /= 2, hits_ /= 2;
    }

private:
    // Measured (`wideray bench`, one thread, 512x512, packet16): at 1/8, bounce rays off the framed
    // teapot, bunny, dragon and coffee maker 1.4-1.9x faster, off framed Sponza (whose packets do
    // better whole) 0.96x; at 1/16 the meshes' 1-6% faster still but Sponza's 0.91x; at 1/32 some
    // packets of diffuse rays part too (the teapot's 0.92x).
    static constexpr float kSpreadFraction = 1.0f / 8.0f;

    float spreadLimit_;
    uint32_t rays_ = 0, hits_ = 0;
};

} // namespace WIDERAY_ISA
} // namespace wideray
