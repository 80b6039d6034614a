#pragma once
// The messages of a distributed render, as bytes: what rank 0 hands out (a work item, or stop) and what
// the other ranks send back (ready for work, a rendered part, or an item's failure).
#include <cstddef>
#include <span>
#include <string>
#include <vector>

#include "render/frame_parts.h"

namespace wideray {

struct RankMessage {
    enum class Kind : uint8_t { Ready, Part, Failure };
    Kind kind = Kind::Ready;
    FramePart part;     ///< Part
    WorkItem item;      ///< Failure: the item that failed
    std::string error;  ///< Failure: what went wrong
};

std::vector<std::byte> encodeMessage(const RankMessage& message);
/// Throws std::runtime_error for bytes that encodeMessage did not write.
RankMessage decodeMessage(std::span<const std::byte> bytes);

/// A work item for a rank; parts = 0 tells it to stop.
struct ItemMessage {
    uint32_t job = 0, part = 0, parts = 0;
};

} // namespace wideray
