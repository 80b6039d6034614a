#include "core/huge_pages.h"

#include <cstdlib>
#include <new>

#include <sys/mman.h>

namespace wideray {

namespace {
constexpr size_t kHugePage = size_t(2) << 20;
}

void* allocateHugePages(size_t bytes) {
    const size_t rounded = (bytes + kHugePage - 1) / kHugePage * kHugePage;
    void* memory = std::aligned_alloc(kHugePage, rounded);
    if (!memory) throw std::bad_alloc();
#ifdef MADV_HUGEPAGE
    madvise(memory, rounded, MADV_HUGEPAGE);  // advice only: without huge pages it still works
#endif
    return memory;
}

void freeHugePages(void* memory) noexcept { std::free(memory); }

} // namespace wideray
