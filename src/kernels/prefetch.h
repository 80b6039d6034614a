#pragma once
// Software prefetch for traversals: a node or leaf that a packet will visit after testing the rest of
// its current node's children is asked for while it does so. Its first load otherwise waits for
// memory: from inside the kitchen, a packet's first read of a leaf block took 14% of its time. A
// single ray goes on to its nearest child right after the test, which leaves a prefetch nothing to
// hide: asking for its leaves (or for the next entry of its stack on a pop) measured slower.
#include <xmmintrin.h>

#include <cstddef>

#include "accel/wide_bvh.h"

#include "simd/isa_namespace.h"

namespace wideray {
inline namespace WIDERAY_ISA {

/// Asks for the cache lines of `bytes` bytes from `p` on.
[[gnu::always_inline]] inline void prefetchLines(const void* p, size_t bytes) {
    const char* c = static_cast<const char*>(p);
    for (size_t line = 0; line < bytes; line += 64) _mm_prefetch(c + line, _MM_HINT_T0);
}

template <int N>
[[gnu::always_inline]] inline void prefetchNode(const WideNode<N>* nodes, NodeRef inner) {
    prefetchLines(&nodes[inner.index()], sizeof(WideNode<N>));
}

} // namespace WIDERAY_ISA
} // namespace wideray
