#include "render/progress.h"

#include <cstdio>

namespace wideray {

ProgressReporter::ProgressReporter(bool enabled, std::string label, size_t total)
    : enabled_(enabled), label_(std::move(label)), total_(total), start_(Clock::now()) {}

void ProgressReporter::tileDone() {
    size_t done = ++done_;
    if (!enabled_) return;
    auto now = Clock::now();
    if (now - start_ < std::chrono::seconds(1)) return;
    std::unique_lock lock(mutex_, std::try_to_lock);
    if (!lock.owns_lock() || (now - lastPrint_ < std::chrono::milliseconds(250) && done != total_)) return;
    lastPrint_ = now;
    printed_ = true;
    std::fprintf(stderr, "\r%s: %3d%%", label_.c_str(), int(100 * done / total_));
    std::fflush(stderr);
}

ProgressReporter::~ProgressReporter() {
    if (printed_) std::fprintf(stderr, "\r%s: 100%%\n", label_.c_str());
}

} // namespace wideray
