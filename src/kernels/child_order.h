#pragma once
// The order in which single-ray traversal visits three or more hit children of a node: each child's
// key is its entry distance as an ordered integer with the lowest bits (three, four for 16-wide
// nodes) replaced by its slot, and
// the children go onto the stack by key, farthest first, so that the nearest is taken next. The keys
// are distinct, so every ISA visits the same nodes: 8-wide ISAs sort all slots at once with a sorting
// network and store the entries with two vector stores (no branch on how the distances compare, which
// no predictor learns); the others insert one child at a time.
#include <bit>
#include <climits>
#include <cstddef>
#include <cstdint>

#include "accel/wide_bvh.h"

#if defined(__AVX2__)
#include <immintrin.h>
#endif

#include "simd/isa_namespace.h"

namespace wideray {
inline namespace WIDERAY_ISA {

/// The low bits of a key of an N-wide node's child that hold its slot.
template <int N>
constexpr int32_t kSlotMask = N <= 8 ? 7 : 15;

/// Increases with the distance (for every float that is not NaN; the low bits break ties by slot).
template <int N = 8>
inline int32_t childOrderKey(float distance, int slot) {
    static_assert(N <= 16, "four bits of the key hold the slot");
    const int32_t bits = std::bit_cast<int32_t>(distance);
    return ((bits ^ int32_t(uint32_t(bits >> 31) >> 1)) & ~kSlotMask<N>) | slot;
}

#if defined(__AVX2__)
/// One step of the network: each lane takes the larger of itself and its partner where MaxLanes has
/// its bit, the smaller elsewhere.
template <int MaxLanes>
[[gnu::always_inline]] inline __m256i compareExchange(__m256i v, __m256i partner) {
    return _mm256_blend_epi32(_mm256_min_epi32(v, partner), _mm256_max_epi32(v, partner), MaxLanes);
}

[[gnu::always_inline]] inline int32_t minimum(__m256i v) {
    v = _mm256_min_epi32(v, _mm256_shuffle_epi32(v, 0xB1));
    v = _mm256_min_epi32(v, _mm256_shuffle_epi32(v, 0x4E));
    return _mm_cvtsi128_si32(_mm_min_epi32(_mm256_castsi256_si128(v), _mm256_extracti128_si256(v, 1)));
}

/// Bitonic sort of eight integers, largest in lane 0: six steps, partners by in-lane shuffles but one.
[[gnu::always_inline]] inline __m256i sortDescending(__m256i v) {
    v = compareExchange<0x99>(v, _mm256_shuffle_epi32(v, 0xB1));     // blocks of 2, partner i ^ 1
    v = compareExchange<0xC3>(v, _mm256_shuffle_epi32(v, 0x4E));     // blocks of 4, i ^ 2
    v = compareExchange<0xA5>(v, _mm256_shuffle_epi32(v, 0xB1));     //              i ^ 1
    v = compareExchange<0x0F>(v, _mm256_permute4x64_epi64(v, 0x4E)); // all 8,       i ^ 4
    v = compareExchange<0x33>(v, _mm256_shuffle_epi32(v, 0x4E));     //              i ^ 2
    return compareExchange<0x55>(v, _mm256_shuffle_epi32(v, 0xB1));  //              i ^ 1
}
#endif

/// Pushes the children in `mask` (three or more) with their entry distances (tEntry, 32-byte aligned),
/// farthest first, and returns the nearest, which the caller descends into. Entry is {NodeRef ref;
/// float distance;}; the stack needs room for N entries beyond sp.
template <int N, class Entry>
[[gnu::always_inline]] inline NodeRef pushNearestLast(Entry* stack, int& sp, const WideNode<N>& node, uint32_t mask,
                                                      const float* tEntry) {
#if defined(__AVX2__)
    if constexpr (N == 8) {
        static_assert(sizeof(Entry) == 8 && offsetof(Entry, distance) == sizeof(NodeRef),
                      "the stores write (ref, distance) pairs");
        const __m256i bits = _mm256_castps_si256(_mm256_load_ps(tEntry));
        const __m256i ordered = _mm256_xor_si256(bits, _mm256_srli_epi32(_mm256_srai_epi32(bits, 31), 1));
        const __m256i slotBits = _mm256_setr_epi32(1, 2, 4, 8, 16, 32, 64, 128);
        const __m256i hit = _mm256_cmpeq_epi32(_mm256_and_si256(_mm256_set1_epi32(int(mask)), slotBits), slotBits);
        __m256i keys = _mm256_or_si256(_mm256_andnot_si256(_mm256_set1_epi32(7), ordered),
                                       _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7));
        // The nearest is found by a minimum, which is shorter than the sort: the descent does not wait
        // for the pushes.
        const int nearest = minimum(_mm256_blendv_epi8(_mm256_set1_epi32(INT_MAX), keys, hit)) & 7;
        keys = _mm256_blendv_epi8(_mm256_set1_epi32(INT_MIN), keys, hit);  // the slots missed sort last
        const __m256i slots = _mm256_and_si256(sortDescending(keys), _mm256_set1_epi32(7));
        const __m256i children = _mm256_load_si256(reinterpret_cast<const __m256i*>(node.child));
        const __m256i refs = _mm256_permutevar8x32_epi32(children, slots);
        const __m256i distances = _mm256_permutevar8x32_epi32(bits, slots);
        const __m256i low = _mm256_unpacklo_epi32(refs, distances), high = _mm256_unpackhi_epi32(refs, distances);
        _mm256_storeu_si256(reinterpret_cast<__m256i*>(stack + sp), _mm256_permute2x128_si256(low, high, 0x20));
        _mm256_storeu_si256(reinterpret_cast<__m256i*>(stack + sp + 4), _mm256_permute2x128_si256(low, high, 0x31));
        sp += __builtin_popcount(mask) - 1;
        return node.child[nearest];
    }
#endif
    int32_t keys[N];
    int count = 0;
    for (; mask; mask &= mask - 1) {
        const int slot = __builtin_ctz(mask);
        const int32_t key = childOrderKey<N>(tEntry[slot], slot);
        int j = count++;
        for (; j > 0 && keys[j - 1] < key; --j) keys[j] = keys[j - 1];
        keys[j] = key;
    }
    for (int k = 0; k < count; ++k) {
        const int slot = keys[k] & kSlotMask<N>;
        stack[sp++] = {node.child[slot], tEntry[slot]};
    }
    return stack[--sp].ref;
}

} // namespace WIDERAY_ISA
} // namespace wideray
