#pragma once
// Whether a render's image fits in memory, checked before anything is allocated: a 65536x65536
// request is refused with its estimate rather than ending in an allocation failure or the OOM killer.
#include <cstdint>
#include <string>

#include "render/render_options.h"

namespace wideray {

/// Bytes a render of `options` (resolved) holds beyond the scene: its film, and the finished image
/// that is written from it.
uint64_t renderBytes(const RenderOptions& options);

/// This machine's physical memory in bytes.
uint64_t physicalMemoryBytes();

/// Throws InputError naming `file` when renderBytes(options) exceeds `available`, with both sizes:
/// "65536x65536 needs 96.0 GiB for its film and image; this machine has 24.0 GiB".
void checkRenderFits(const RenderOptions& options, const std::string& file, uint64_t available = physicalMemoryBytes());

} // namespace wideray
