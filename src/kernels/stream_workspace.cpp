#include "kernels/stream_workspace.h"

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <new>

namespace wideray {
namespace {

constexpr int kFloatArrays = 13, kIntArrays = 5, kIdArrays = 6;

void* allocate(size_t bytes) {
    void* p = std::aligned_alloc(64, (bytes + 63) / 64 * 64);
    if (!p) throw std::bad_alloc();
    return p;
}

} // namespace

StreamWorkspace::~StreamWorkspace() {
    std::free(ox);
    std::free(arena);
    std::free(arenaEntry);
    std::free(stack);
}

void StreamWorkspace::reserveRays(size_t n) {
    if (n <= capacity) return;
    size_t stride = (n + 15) / 16 * 16;  // keeps every array 64-byte aligned
    size_t bytes = stride * (4 * (kFloatArrays + kMaxStreamNodeWidth + kIntArrays + kIdArrays) + 2 * sizeof(uint64_t) + 1);
    char* block = static_cast<char*>(allocate(bytes));
    std::free(ox);
    float** floats[kFloatArrays] = {&ox, &oy, &oz, &rdx, &rdy, &rdz, &tnear, &tfar, &sx, &sy, &sz, &u, &v};
    for (float** f : floats) {
        *f = reinterpret_cast<float*>(block);
        block += stride * 4;
    }
    childEntries = reinterpret_cast<float*>(block);
    block += stride * 4 * kMaxStreamNodeWidth;
    for (int32_t** a : {&kx, &ky, &kz, &prim, &visits}) {
        *a = reinterpret_cast<int32_t*>(block);
        block += stride * 4;
    }
    keys = reinterpret_cast<uint64_t*>(block);
    block += stride * 8;
    sortScratch = reinterpret_cast<uint64_t*>(block);
    block += stride * 8;
    for (uint32_t** a : {&rayOf, &userGeomId, &userPrimId, &costNodes, &costLeaves, &costPrimitives}) {
        *a = reinterpret_cast<uint32_t*>(block);
        block += stride * 4;
    }
    valid = reinterpret_cast<uint8_t*>(block);
    capacity = stride;
}

void StreamWorkspace::reserveArena(size_t n) {
    if (n <= arenaCapacity) return;
    size_t grown = std::max(n, arenaCapacity * 2);
    auto* bigger = static_cast<int32_t*>(allocate(grown * sizeof(int32_t)));
    float* biggerEntry;
    try {
        biggerEntry = static_cast<float*>(allocate(grown * sizeof(float)));
    } catch (...) {
        std::free(bigger);
        throw;
    }
    if (arena) {
        std::memcpy(bigger, arena, arenaCapacity * sizeof(int32_t));
        std::memcpy(biggerEntry, arenaEntry, arenaCapacity * sizeof(float));
    }
    std::free(arena);
    std::free(arenaEntry);
    arena = bigger;
    arenaEntry = biggerEntry;
    arenaCapacity = grown;
}

void* StreamWorkspace::reserveStack(size_t bytes) {
    if (bytes > stackBytes) {
        void* bigger = allocate(bytes);
        std::free(stack);
        stack = bigger;
        stackBytes = bytes;
    }
    return stack;
}

StreamWorkspace& StreamWorkspace::forThisThread() {
    thread_local StreamWorkspace workspace;
    return workspace;
}

// Least significant digit first, 11 bits a pass over the 33 bits above the index: three counting
// passes, each stable, so the index order of the input survives among equal codes.
void StreamWorkspace::sortKeys(size_t count) {
    constexpr int kDigitBits = 11, kPasses = 3;
    static_assert(kKeyIndexBits + kDigitBits * kPasses == 64);
    uint64_t *from = keys, *to = sortScratch;
    for (int pass = 0; pass < kPasses; ++pass) {
        const int shift = kKeyIndexBits + pass * kDigitBits;
        uint32_t start[(1 << kDigitBits) + 1] = {};
        for (size_t i = 0; i < count; ++i) ++start[((from[i] >> shift) & ((1 << kDigitBits) - 1)) + 1];
        for (int d = 1; d <= (1 << kDigitBits); ++d) start[d] += start[d - 1];
        for (size_t i = 0; i < count; ++i) to[start[(from[i] >> shift) & ((1 << kDigitBits) - 1)]++] = from[i];
        std::swap(from, to);
    }
    if (from != keys) std::memcpy(keys, from, count * sizeof(uint64_t));
}

} // namespace wideray
