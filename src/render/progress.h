#pragma once
// Progress of a render on stderr.
#include <atomic>
#include <chrono>
#include <mutex>
#include <string>

namespace wideray {

/// Prints "label: 42%" on stderr, at most every quarter second, once the render has run a second.
class ProgressReporter {
public:
    ProgressReporter(bool enabled, std::string label, size_t total);
    ~ProgressReporter();

    /// One more of the `total` units of work is done (any thread).
    void tileDone();

private:
    using Clock = std::chrono::steady_clock;
    bool enabled_;
    std::string label_;
    size_t total_;
    std::atomic<size_t> done_{0};
    Clock::time_point start_, lastPrint_;
    std::mutex mutex_;
    bool printed_ = false;
};

} // namespace wideray
