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
    std::free(stack);
}

void StreamWorkspace::reserveRays(size_t n) {
    if (n <= capacity) return;
    size_t stride = (n + 15) / 16 * 16;  // keeps every array 64-byte aligned
    size_t bytes = stride * (4 * (kFloatArrays + kIntArrays + kIdArrays) + sizeof(uint64_t) + 1);
    char* block = static_cast<char*>(allocate(bytes));
    std::free(ox);
    float** floats[kFloatArrays] = {&ox, &oy, &oz, &rdx, &rdy, &rdz, &tnear, &tfar, &sx, &sy, &sz, &u, &v};
    for (float** f : floats) {
        *f = reinterpret_cast<float*>(block);
        block += stride * 4;
    }
    for (int32_t** a : {&kx, &ky, &kz, &prim, &visits}) {
        *a = reinterpret_cast<int32_t*>(block);
        block += stride * 4;
    }
    keys = reinterpret_cast<uint64_t*>(block);
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
    if (arena) std::memcpy(bigger, arena, arenaCapacity * sizeof(int32_t));
    std::free(arena);
    arena = bigger;
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

void sortStreamKeys(uint64_t* keys, size_t count) { std::sort(keys, keys + count); }

} // namespace wideray
