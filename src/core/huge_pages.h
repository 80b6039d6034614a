#pragma once
// Large arrays in 2 MiB pages where the kernel offers them on request (Linux transparent huge pages
// in "madvise" mode, Debian's default): a build writes hundreds of MB of fresh memory, and with 4 KiB
// pages a third of its time went to page faults (one per 4 KiB; one per 2 MiB here). Embree's
// allocator asks for them too.
#include <cstddef>

namespace wideray {

/// Allocations of at least this many bytes take the huge-page path. Below 8 MiB, clearing whole 2 MiB
/// pages (and the kernel's compaction for them) cost more than the faults they save: with 4 MiB the
/// dragon's fast build took 14.4 ms against 12.8 ms with 16 MiB (and 13.0 ms without huge pages).
/// From 8 MiB (a process's first build, one thread, `wideray info`): Sponza's fast build 86 -> 61 ms
/// and high 160 -> 137 ms, the coffee maker's 96 -> 66 and 122 -> 95 ms, the kitchen's high 571 ->
/// 533 ms against 16 MiB (their wide nodes, leaf blocks and collapse plans are 8-16 MiB); the dragon
/// and the bunny have no array that large.
constexpr size_t kHugePageMinBytes = size_t(8) << 20;

/// Memory for `bytes` (at least kHugePageMinBytes), 2 MiB aligned, advised to use huge pages; throws
/// std::bad_alloc. Freed by freeHugePages.
void* allocateHugePages(size_t bytes);
void freeHugePages(void* memory) noexcept;

} // namespace wideray
