#pragma once
// The kernel registry: one table per ISA, one row per kernel, each row a kernel's name, what it is,
// its Embree counterpart and its entry points. The rows are the same in every table (those an ISA
// cannot run have null entry points) and are written once, in isa_kernels.inl, which each thin
// translation unit in kernels/isa/ compiles with its ISA's flags. The CLI, the tracers, bench,
// tests and perf iterate the table: a new kernel is one header and one row.
#include <array>
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "accel/bvh_view.h"
#include "core/ray.h"
#include "kernels/shadow_cache.h"
#include "simd/cpu_features.h"

namespace wideray {

template <int N>
struct Kernel {
    using IntersectFn = void (*)(const SceneView<N>&, const Ray*, Hit*, size_t, TraversalCost*);
    using OccludedFn = void (*)(const SceneView<N>&, const Ray*, uint8_t*, size_t, TraversalCost*);
    /// Occlusion with a shadow cache (the single-ray kernel and the packets).
    using OccludedCachedFn = void (*)(const SceneView<N>&, const Ray*, uint8_t*, size_t, ShadowCache&);

    const char* name = "";
    const char* description = "";
    const char* embreeCounterpart = "";  ///< the Embree entry point bench compares it with ("" for none)
    Isa minimumIsa = Isa::Sse42;         ///< the ISA it needs at least
    IntersectFn intersect = nullptr;     ///< null where this table's ISA cannot run it
    OccludedFn occluded = nullptr;
    OccludedCachedFn occludedCached = nullptr;

    bool available() const { return intersect != nullptr; }
};

/// Every kernel; rows[0] is the scalar reference, compiled for the table's ISA like the rest: the
/// kernels of a table reproduce its reference bit for bit.
template <int N>
struct KernelTable {
    static constexpr size_t kCount = 8;
    std::array<Kernel<N>, kCount> rows;

    /// The row named `name`, or null.
    const Kernel<N>* find(std::string_view name) const {
        for (const Kernel<N>& k : rows)
            if (name == k.name) return &k;
        return nullptr;
    }
};

template <int N> KernelTable<N> sse42KernelTable();
template <int N> KernelTable<N> avx2KernelTable();
template <int N> KernelTable<N> avx512KernelTable();

/// The table of an ISA; the caller checks cpuSupports(isa) first.
template <int N>
KernelTable<N> kernelTable(Isa isa) {
    switch (isa) {
    case Isa::Avx512: return avx512KernelTable<N>();
    case Isa::Avx2: return avx2KernelTable<N>();
    case Isa::Sse42: break;
    }
    return sse42KernelTable<N>();
}

/// The scalar reference of an ISA.
template <int N>
Kernel<N> referenceKernel(Isa isa) {
    return kernelTable<N>(isa).rows[0];
}

} // namespace wideray
