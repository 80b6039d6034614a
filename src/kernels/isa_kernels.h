#pragma once
// The kernels each ISA provides, as plain function pointers. The tables are defined by the thin
// per-ISA translation units in kernels/isa/ and read by the baseline dispatch code.
#include "kernels/kernel_set.h"
#include "simd/cpu_features.h"

namespace wideray {

/// Kernels one ISA can run; a null function pointer means the ISA lacks the width.
template <int N>
struct IsaKernelTable {
    KernelSet<N> single;  ///< one ray at a time, SIMD across the N children and the M triangles of a block
    KernelSet<N> packet4, packet8, packet16;
    KernelSet<N> packet256;  ///< 256-ray packets with interval culling, sub-packets of the widest vector
    KernelSet<N> stream;  ///< sorted ray streams, one list per child
    KernelSet<N> drst;    ///< sorted ray streams, each ray in its own order (Dynamic Ray Stream Traversal)
};

template <int N> IsaKernelTable<N> sse42KernelTable();
template <int N> IsaKernelTable<N> avx2KernelTable();
template <int N> IsaKernelTable<N> avx512KernelTable();

/// The table of an ISA; the caller checks cpuSupports(isa) first.
template <int N>
IsaKernelTable<N> kernelTable(Isa isa) {
    switch (isa) {
    case Isa::Avx512: return avx512KernelTable<N>();
    case Isa::Avx2: return avx2KernelTable<N>();
    case Isa::Sse42: break;
    }
    return sse42KernelTable<N>();
}

} // namespace wideray
