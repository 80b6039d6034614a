#pragma once
// Memory of the stream kernel, per thread and reused across streams. It is allocated and sorted by
// baseline code so that no standard-library code is instantiated with AVX flags (the linker could
// otherwise hand an AVX-512 copy of it to code running on a CPU without AVX-512).
#include <cstddef>
#include <cstdint>

namespace wideray {

struct StreamWorkspace {
    // Per ray of the stream, in sorted order.
    float *ox = nullptr, *oy = nullptr, *oz = nullptr, *rdx = nullptr, *rdy = nullptr, *rdz = nullptr;
    float *tnear = nullptr, *tfar = nullptr, *sx = nullptr, *sy = nullptr, *sz = nullptr, *u = nullptr, *v = nullptr;
    int32_t *kx = nullptr, *ky = nullptr, *kz = nullptr, *prim = nullptr;
    int32_t* visits = nullptr;  ///< per ray of the list being split: its children and their order
    /// Per ray of the list being split, kMaxStreamNodeWidth of them: its entries into the children
    /// (chunk by chunk: K rays' entries into the child in slot 0, then slot 1, ...).
    float* childEntries = nullptr;
    uint32_t* rayOf = nullptr;  ///< stream slot -> index in the caller's array
    uint32_t *userGeomId = nullptr, *userPrimId = nullptr;  ///< the ids of closest hits on user primitives
    uint32_t *costNodes = nullptr, *costLeaves = nullptr, *costPrimitives = nullptr;  ///< traversal work, when counted
    bool countCost = false;
    /// Sort keys: the direction octant in bits 61..63, a Morton code of the origin in bits 31..60,
    /// the ray's index in bits 0..30 (kKeyIndexBits).
    uint64_t* keys = nullptr;
    uint64_t* sortScratch = nullptr;
    uint8_t* valid = nullptr;   ///< per ray of the caller's array: whether it is traced at all
    size_t capacity = 0;
    int32_t* arena = nullptr;   ///< the ray lists of the nodes waiting on the traversal stack
    float* arenaEntry = nullptr;  ///< beside each arena entry: where its ray enters the list's node
    size_t arenaCapacity = 0;
    void* stack = nullptr;      ///< the traversal stack (its entry type belongs to the kernel)
    size_t stackBytes = 0;

    StreamWorkspace() = default;
    StreamWorkspace(const StreamWorkspace&) = delete;
    StreamWorkspace& operator=(const StreamWorkspace&) = delete;
    ~StreamWorkspace();

    void reserveRays(size_t n);
    /// Grows the arena to at least n entries, keeping its contents.
    void reserveArena(size_t n);
    /// Grows the stack to at least `bytes` (its contents are not kept) and returns it.
    void* reserveStack(size_t bytes);
    /// Sorts keys[0, count) by octant and Morton code; rays with equal codes stay in index order.
    void sortKeys(size_t count);

    static StreamWorkspace& forThisThread();
};

constexpr int kKeyIndexBits = 31;
/// The widest node a stream traverses (childEntries has room for its children).
constexpr int kMaxStreamNodeWidth = 8;

} // namespace wideray
