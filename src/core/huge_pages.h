#pragma once
// Large arrays in 2 MiB pages where the kernel offers them on request (Linux transparent huge pages
// in "madvise" mode, Debian's default): a build writes hundreds of MB of fresh memory, and with 4 KiB
// pages a third of its time went to page faults (one per 4 KiB; one per 2 MiB here). Embree's
// allocator asks for them too.
#include <cstddef>

namespace wideray {

/// Allocations of at least this many bytes take the huge-page path. Below it, clearing whole 2 MiB
/// pages (and the kernel's compaction for them) cost more than the faults they save: with 4 MiB the
/// dragon's fast build took 14.4 ms against 12.8 ms with 16 MiB (and 13.0 ms without huge pages);
/// Sponza's and the kitchen's large arrays gain at either.
constexpr size_t kHugePageMinBytes = size_t(16) << 20;

/// Memory for `bytes` (at least kHugePageMinBytes), 2 MiB aligned, advised to use huge pages; throws
/// std::bad_alloc. Freed by freeHugePages.
void* allocateHugePages(size_t bytes);
void freeHugePages(void* memory) noexcept;

} // namespace wideray
