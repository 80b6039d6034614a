#pragma once
// The order in which single-ray traversal visits three or more hit children of a node: each child's
// key is its entry distance as an ordered integer with the lowest bits (three, four for 16-wide
// nodes) replaced by its slot, and
// the children go onto the stack by key, farthest first, so that the nearest is taken next. The keys
// are distinct, so every ISA visits the same nodes: 8-wide ISAs sort all slots of an 8-wide node at
// once with a sorting network and store the entries with two vector stores (no branch on how the
// distances compare, which no predictor learns), AVX-512 those of a 16-wide node with a network of
// ten steps; the others insert one child at a time.
#include <bit>
#include <climits>
#include <cstddef>
#include <cstdint>

#include "accel/wide_bvh.h"

#if defined(__AVX2__) || defined(__AVX512F__)
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

#if defined(__AVX512F__)
/// The lanes of a descending bitonic network's step (blocks of K, partners i ^ J) that keep the larger.
constexpr __mmask16 maxLanes(int k, int j) {
    __mmask16 lanes = 0;
    for (int i = 0; i < 16; ++i)
        if (((i & j) == 0) == ((i & k) == 0)) lanes = __mmask16(lanes | 1 << i);
    return lanes;
}

template <int K, int J>
[[gnu::always_inline]] inline __m512i compareExchange16(__m512i v) {
    __m512i partner;
    if constexpr (J == 1) partner = _mm512_shuffle_epi32(v, _MM_PERM_CDAB);
    else if constexpr (J == 2) partner = _mm512_shuffle_epi32(v, _MM_PERM_BADC);
    else if constexpr (J == 4) partner = _mm512_shuffle_i32x4(v, v, 0xB1);  // 128-bit lanes 1, 0, 3, 2
    else partner = _mm512_shuffle_i32x4(v, v, 0x4E);                       // 256-bit halves swapped
    return _mm512_mask_max_epi32(_mm512_min_epi32(v, partner), maxLanes(K, J), v, partner);
}

/// Bitonic sort of sixteen integers, largest in lane 0: ten steps.
[[gnu::always_inline]] inline __m512i sortDescending16(__m512i v) {
    v = compareExchange16<2, 1>(v);
    v = compareExchange16<4, 2>(v);
    v = compareExchange16<4, 1>(v);
    v = compareExchange16<8, 4>(v);
    v = compareExchange16<8, 2>(v);
    v = compareExchange16<8, 1>(v);
    v = compareExchange16<16, 8>(v);
    v = compareExchange16<16, 4>(v);
    v = compareExchange16<16, 2>(v);
    return compareExchange16<16, 1>(v);
}
#endif

/// Pushes the children in `mask` (three or more) with their entry distances (tEntry, 64-byte aligned),
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
#if defined(__AVX512F__)
    if constexpr (N == 16) {
        static_assert(sizeof(Entry) == 8 && offsetof(Entry, distance) == sizeof(NodeRef),
                      "the stores write (ref, distance) pairs");
        const __m512i bits = _mm512_castps_si512(_mm512_load_ps(tEntry));
        const __m512i ordered = _mm512_xor_si512(bits, _mm512_srli_epi32(_mm512_srai_epi32(bits, 31), 1));
        const __m512i slotMask = _mm512_set1_epi32(kSlotMask<16>);
        __m512i keys = _mm512_or_si512(_mm512_andnot_si512(slotMask, ordered),
                                       _mm512_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15));
        const __mmask16 hit = __mmask16(mask);
        const int nearest = _mm512_mask_reduce_min_epi32(hit, keys) & kSlotMask<16>;  // beside the sort, as above
        keys = _mm512_mask_mov_epi32(_mm512_set1_epi32(INT_MIN), hit, keys);      // the slots missed sort last
        const __m512i slots = _mm512_and_si512(sortDescending16(keys), slotMask);
        const __m512i refs = _mm512_permutexvar_epi32(slots, _mm512_loadu_si512(node.child));
        const __m512i distances = _mm512_permutexvar_epi32(slots, bits);
        const __m512i firstPairs = _mm512_setr_epi32(0, 16, 1, 17, 2, 18, 3, 19, 4, 20, 5, 21, 6, 22, 7, 23);
        const __m512i lastPairs = _mm512_add_epi32(firstPairs, _mm512_set1_epi32(8));
        _mm512_storeu_si512(stack + sp, _mm512_permutex2var_epi32(refs, firstPairs, distances));
        _mm512_storeu_si512(stack + sp + 8, _mm512_permutex2var_epi32(refs, lastPairs, distances));
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
