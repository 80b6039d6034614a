#pragma once
// A batch of frames rendered by the ranks of an MPI job (mpirun -np N wideray render ...). Rank 0
// hands out work items on request (whole frames when the batch has at least as many frames as there
// are ranks, else runs of each frame's tiles) and renders items itself on a second thread; the other
// ranks render an item, send it back with the request for the next, and stop when told. Rank 0 joins
// the parts of each frame and hands the whole image on (to be written). Every rank renders with all of
// its oneTBB threads. MPI is called from each process's main thread alone (MPI_THREAD_FUNNELED).
#include <cstdint>
#include <functional>
#include <string>

#include "core/image.h"
#include "render/frame_parts.h"

namespace wideray {

/// MPI for the life of this object: initialized on construction, finalized on destruction.
class MpiSession {
public:
    MpiSession();
    ~MpiSession();
    MpiSession(const MpiSession&) = delete;
    MpiSession& operator=(const MpiSession&) = delete;

    int rank() const { return rank_; }
    int size() const { return size_; }

private:
    int rank_ = 0, size_ = 1;
};

/// A frame that rank 0 has joined from its parts.
struct FrameSummary {
    RenderStats stats;        ///< the rays of every part; seconds: from handing out its first part to the last part in
    FramePart description;    ///< size, samples, triangles, names (no film values)
    double slowestBuild = 0;  ///< the longest any rank took to build the structure for it
    int ranks = 0;            ///< how many ranks rendered parts of it
};

struct DistributedBatch {
    uint32_t jobs = 0;
    bool progress = false;  ///< rank 0 reports the share of items done on stderr
    /// Renders a work item (every rank; on rank 0 from its rendering thread). Throws on failure.
    std::function<FramePart(const WorkItem&)> renderPart;
    /// Rank 0: job's frame is whole (writes it). Throws on failure.
    std::function<void(uint32_t job, Image&& image, const FrameSummary& summary)> frameDone;
    /// Rank 0: job failed on `rank` with `message`; called once per job, the job's other parts dropped.
    /// Rank 0 calls frameDone and frameFailed from one thread of their own, in the order frames end,
    /// so that writing an image never keeps the other ranks waiting for work.
    std::function<void(uint32_t job, const std::string& message, int rank)> frameFailed;
};

/// How many parts each frame is cut into: 1 (whole frames) when there are at least as many frames as
/// ranks, else 4 per rank, so that ranks that finish early take more.
uint32_t partsPerFrame(uint32_t jobs, int ranks);

/// Renders the batch on every rank of `session`; returns on each rank once every item is done.
/// Rank 0 calls frameDone or frameFailed once per job.
void renderDistributed(const MpiSession& session, const DistributedBatch& batch);

} // namespace wideray
