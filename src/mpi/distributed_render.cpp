#include "mpi/distributed_render.h"

#include <algorithm>
#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <deque>
#include <memory>
#include <mutex>
#include <optional>
#include <set>
#include <stdexcept>
#include <thread>
#include <vector>

#include <fmt/core.h>
#include <mpi.h>

#include "core/fp_mode.h"
#include "mpi/part_message.h"
#include "render/progress.h"

namespace wideray {
namespace {

using Clock = std::chrono::steady_clock;

constexpr int kTagToRoot = 1;  ///< ready / part / failure, to rank 0
constexpr int kTagItem = 2;    ///< a work item or stop, from rank 0
constexpr size_t kChunkBytes = size_t(1) << 30;  ///< MPI counts are ints: larger parts go in pieces

void check(int rc, const char* call) {
    if (rc != MPI_SUCCESS) throw std::runtime_error(std::string("MPI: ") + call + " failed");
}

/// Waits for a message without spinning: OpenMPI's blocking receive polls on a core, which a rank of
/// an oversubscribed job would take from the render threads of its own or another rank. The pause
/// between polls grows from 20 us (a reply that is on its way) to 2 ms (a rank still rendering).
MPI_Status waitFor(int source, int tag) {
    for (auto pause = std::chrono::microseconds(20);; pause = std::min(pause * 2, std::chrono::microseconds(2000))) {
        int arrived = 0;
        MPI_Status status;
        check(MPI_Iprobe(source, tag, MPI_COMM_WORLD, &arrived, &status), "MPI_Iprobe");
        if (arrived) return status;
        std::this_thread::sleep_for(pause);
    }
}

/// A byte message: its length, then its bytes in chunks.
void sendBytes(const std::vector<std::byte>& bytes, int destination, int tag) {
    const uint64_t size = bytes.size();
    check(MPI_Send(&size, 1, MPI_UINT64_T, destination, tag, MPI_COMM_WORLD), "MPI_Send");
    for (size_t offset = 0; offset < bytes.size(); offset += kChunkBytes)
        check(MPI_Send(bytes.data() + offset, int(std::min(kChunkBytes, bytes.size() - offset)), MPI_BYTE, destination,
                       tag, MPI_COMM_WORLD),
              "MPI_Send");
}

std::vector<std::byte> receiveBytes(int source, int tag) {
    uint64_t size = 0;
    check(MPI_Recv(&size, 1, MPI_UINT64_T, source, tag, MPI_COMM_WORLD, MPI_STATUS_IGNORE), "MPI_Recv");
    std::vector<std::byte> bytes(size);
    for (size_t offset = 0; offset < bytes.size(); offset += kChunkBytes)
        check(MPI_Recv(bytes.data() + offset, int(std::min(kChunkBytes, bytes.size() - offset)), MPI_BYTE, source, tag,
                       MPI_COMM_WORLD, MPI_STATUS_IGNORE),
              "MPI_Recv");
    return bytes;
}

/// Rank 0's thread for the batch's frameDone and frameFailed: writing an image takes long (a quarter
/// second for a megapixel PNG), and the ranks asking for work must not wait for it. At most kQueued
/// frames wait to be written; beyond that the writer is what limits the batch, and done() waits.
class FrameOutbox {
public:
    explicit FrameOutbox(const DistributedBatch& batch) : batch_(batch), thread_([this] { run(); }) {}
    ~FrameOutbox() {
        {
            std::lock_guard lock(mutex_);
            closed_ = true;
        }
        changed_.notify_all();
        thread_.join();
    }

    void done(uint32_t job, Image&& image, FrameSummary&& summary) {
        std::unique_lock lock(mutex_);
        changed_.wait(lock, [&] { return queue_.size() < kQueued; });
        queue_.push_back({job, std::move(image), std::move(summary), {}, 0});
        changed_.notify_all();
    }
    void failed(uint32_t job, const std::string& message, int rank) {
        std::lock_guard lock(mutex_);
        queue_.push_back({job, std::nullopt, {}, message, rank});
        changed_.notify_all();
    }

private:
    static constexpr size_t kQueued = 4;
    struct Entry {
        uint32_t job;
        std::optional<Image> image;  ///< none: the job failed
        FrameSummary summary;
        std::string message;
        int rank;
    };

    void run() {
        for (;;) {
            std::unique_lock lock(mutex_);
            changed_.wait(lock, [&] { return closed_ || !queue_.empty(); });
            if (queue_.empty()) return;
            Entry entry = std::move(queue_.front());
            queue_.pop_front();
            lock.unlock();
            changed_.notify_all();
            if (entry.image) {
                try {
                    batch_.frameDone(entry.job, std::move(*entry.image), entry.summary);
                    continue;
                } catch (const std::exception& e) {
                    entry.message = e.what();
                }
            }
            try {
                batch_.frameFailed(entry.job, entry.message, entry.rank);
            } catch (const std::exception& e) {
                std::fprintf(stderr, "error: %s\n", e.what());  // reporting failed too; the frame stays failed
            }
        }
    }

    const DistributedBatch& batch_;
    std::mutex mutex_;
    std::condition_variable changed_;
    std::deque<Entry> queue_;
    bool closed_ = false;
    std::thread thread_;
};

/// Rank 0's book of the batch: the items not yet handed out, and each frame's parts as they come in.
/// Its main thread (for the other ranks) and its rendering thread use it at once.
class Dispatcher {
public:
    Dispatcher(const DistributedBatch& batch, uint32_t parts, int ranks, FrameOutbox& outbox)
        : batch_(batch), parts_(parts), jobs_(batch.jobs), outbox_(outbox),
          progress_(batch.progress, fmt::format("{} frame{} on {} rank{}", batch.jobs, batch.jobs == 1 ? "" : "s", ranks,
                                                ranks == 1 ? "" : "s"),
                    size_t(batch.jobs) * parts) {}

    /// The next item, skipping frames that failed; none once all are handed out, or once stopped.
    std::optional<WorkItem> next() {
        std::lock_guard lock(mutex_);
        if (stopped_) return std::nullopt;
        while (job_ < batch_.jobs && jobs_[job_].failed) {
            ++job_;
            part_ = 0;
        }
        if (job_ >= batch_.jobs) return std::nullopt;
        const WorkItem item{job_, part_, parts_};
        if (part_ == 0) jobs_[job_].start = Clock::now();
        if (++part_ == parts_) {
            ++job_;
            part_ = 0;
        }
        return item;
    }

    void finished(int rank, FramePart&& part) {
        std::unique_lock lock(mutex_);
        const uint32_t job = part.item.job;
        if (job >= batch_.jobs) throw std::runtime_error("rank " + std::to_string(rank) + " sent a part of no job");
        progress_.tileDone();
        Job& j = jobs_[job];
        if (j.failed || j.done) return;
        try {
            j.ranks.insert(rank);
            if (!j.assembler) j.assembler = std::make_unique<FrameAssembler>();
            if (!j.assembler->add(std::move(part))) return;
            FrameSummary summary;
            Image image = j.assembler->finish(summary.stats);
            summary.stats.seconds = std::chrono::duration<double>(Clock::now() - j.start).count();
            summary.description = j.assembler->description();
            summary.slowestBuild = j.assembler->slowestBuild();
            summary.ranks = int(j.ranks.size());
            j.done = true;
            j.assembler.reset();
            lock.unlock();
            outbox_.done(job, std::move(image), std::move(summary));
        } catch (const std::exception& e) {
            if (!lock.owns_lock()) lock.lock();
            fail(job, e.what(), 0);
        }
    }

    /// No more items, for anyone: the batch is being abandoned.
    void stop() {
        std::lock_guard lock(mutex_);
        stopped_ = true;
    }

    void failed(int rank, const WorkItem& item, const std::string& message) {
        std::lock_guard lock(mutex_);
        if (item.job >= batch_.jobs) throw std::runtime_error("rank " + std::to_string(rank) + " failed on no job");
        progress_.tileDone();
        fail(item.job, message, rank);
    }

private:
    struct Job {
        std::unique_ptr<FrameAssembler> assembler;
        std::set<int> ranks;
        Clock::time_point start;
        bool failed = false, done = false;
    };

    /// With the lock held.
    void fail(uint32_t job, const std::string& message, int rank) {
        Job& j = jobs_[job];
        if (j.failed || j.done) return;
        j.failed = true;
        j.assembler.reset();
        outbox_.failed(job, message, rank);
    }

    const DistributedBatch& batch_;
    const uint32_t parts_;
    std::mutex mutex_;
    std::vector<Job> jobs_;
    FrameOutbox& outbox_;
    uint32_t job_ = 0, part_ = 0;
    bool stopped_ = false;
    ProgressReporter progress_;  ///< items done, on stderr
};

/// Rank 0's own share: items rendered until none are left.
void renderOwnItems(const DistributedBatch& batch, Dispatcher& dispatcher) {
    while (const std::optional<WorkItem> item = dispatcher.next()) {
        try {
            dispatcher.finished(0, batch.renderPart(*item));
        } catch (const std::exception& e) {
            dispatcher.failed(0, *item, e.what());
        }
    }
}

void serveAndRender(const MpiSession& session, const DistributedBatch& batch) {
    FrameOutbox outbox(batch);
    Dispatcher dispatcher(batch, partsPerFrame(batch.jobs, session.size()), session.size(), outbox);
    std::thread own([&] {
        FlushToZeroScope ftz;  // a thread of its own: its tasks do not inherit the caller's mode
        ftz.run([&] { renderOwnItems(batch, dispatcher); });
    });
    struct Join {
        std::thread& thread;
        ~Join() { thread.join(); }
    } join{own};
    try {
        for (int active = session.size() - 1; active > 0;) {
            const int source = waitFor(MPI_ANY_SOURCE, kTagToRoot).MPI_SOURCE;
            RankMessage message = decodeMessage(receiveBytes(source, kTagToRoot));
            if (message.kind == RankMessage::Kind::Part)
                dispatcher.finished(source, std::move(message.part));
            else if (message.kind == RankMessage::Kind::Failure)
                dispatcher.failed(source, message.item, message.error);
            const std::optional<WorkItem> item = dispatcher.next();
            const ItemMessage reply = item ? ItemMessage{item->job, item->part, item->parts} : ItemMessage{};
            check(MPI_Send(&reply, sizeof(reply), MPI_BYTE, source, kTagItem, MPI_COMM_WORLD), "MPI_Send");
            if (!item) --active;
        }
    } catch (...) {
        dispatcher.stop();  // rank 0's own thread ends with its item, and the abort follows
        throw;
    }
}

void renderRequestedItems(const DistributedBatch& batch) {
    RankMessage message;  // first: ready
    for (;;) {
        sendBytes(encodeMessage(message), 0, kTagToRoot);
        waitFor(0, kTagItem);
        ItemMessage item;
        check(MPI_Recv(&item, sizeof(item), MPI_BYTE, 0, kTagItem, MPI_COMM_WORLD, MPI_STATUS_IGNORE), "MPI_Recv");
        if (item.parts == 0) return;
        const WorkItem work{item.job, item.part, item.parts};
        message = {};
        try {
            message.part = batch.renderPart(work);
            message.kind = RankMessage::Kind::Part;
        } catch (const std::exception& e) {
            message.kind = RankMessage::Kind::Failure;
            message.item = work;
            message.error = e.what();
        }
    }
}

} // namespace

MpiSession::MpiSession() {
    int provided = 0;
    check(MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided), "MPI_Init_thread");
    if (provided < MPI_THREAD_FUNNELED) {
        MPI_Finalize();
        throw std::runtime_error("MPI: this MPI library cannot be used by a multithreaded process (MPI_THREAD_FUNNELED)");
    }
    MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
    MPI_Comm_size(MPI_COMM_WORLD, &size_);
}

MpiSession::~MpiSession() { MPI_Finalize(); }

uint32_t partsPerFrame(uint32_t jobs, int ranks) {
    if (ranks <= 1 || jobs >= uint32_t(ranks)) return 1;
    return 4 * uint32_t(ranks);
}

void renderDistributed(const MpiSession& session, const DistributedBatch& batch) {
    try {
        if (session.rank() == 0)
            serveAndRender(session, batch);
        else
            renderRequestedItems(batch);
    } catch (const std::exception& e) {
        // A broken exchange leaves the other ranks waiting: end them all.
        std::fprintf(stderr, "error: rank %d: %s\n", session.rank(), e.what());
        MPI_Abort(MPI_COMM_WORLD, 2);
    }
}

} // namespace wideray
