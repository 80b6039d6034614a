#pragma once
// pushNearestLast (kernels/child_order.h) on one node, for the tests: compiled in the baseline test
// sources and, in avx2_checks.cpp, with AVX2 flags, where it takes the sorting network.
#include <cstdint>

#include "kernels/child_order.h"

namespace wideray::test {

struct ChildOrderResult {
    uint32_t refs[16];      ///< what went onto the stack, bottom first
    float distances[16];
    int pushed = 0;
    uint32_t next = 0;      ///< the child returned to descend into
    uint32_t below = 0;     ///< the entry under the pushed ones, which must be left as it was
};

inline namespace WIDERAY_ISA {

/// An N-wide node whose slot i holds inner child 100 + i, entered at distances[i]; the stack holds
/// one entry.
template <int N = 8>
inline ChildOrderResult runPushNearestLast(const float* distances, uint32_t mask) {
    WideNode<N> node{};
    alignas(64) float tEntry[N];
    for (int i = 0; i < N; ++i) {
        node.child[i] = NodeRef::inner(100 + uint32_t(i));
        tEntry[i] = distances[i];
    }
    struct Entry {
        NodeRef ref;
        float distance;
    };
    Entry stack[1 + N + N];
    int sp = 0;
    stack[sp++] = {NodeRef::inner(7), 0.0f};
    const NodeRef next = pushNearestLast(stack, sp, node, mask, tEntry);
    ChildOrderResult r;
    r.pushed = sp - 1;
    for (int k = 0; k < r.pushed; ++k) {
        r.refs[k] = stack[1 + k].ref.bits;
        r.distances[k] = stack[1 + k].distance;
    }
    r.next = next.bits;
    r.below = stack[0].ref.bits;
    return r;
}

} // namespace WIDERAY_ISA

/// The same compiled for AVX2 (avx2_checks.cpp): call only where the CPU has it.
ChildOrderResult runPushNearestLastAvx2(const float* distances, uint32_t mask);
/// A 16-wide node's, compiled for AVX-512 (avx512_checks.cpp, the sorting network): call only where
/// the CPU has it.
ChildOrderResult runPushNearestLast16Avx512(const float* distances, uint32_t mask);

} // namespace wideray::test
