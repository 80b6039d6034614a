// wideray render under mpirun: the batch's frames (or, when there are fewer frames than ranks, runs of
// their tiles) are work items that rank 0 hands out (mpi/distributed_render.h); rank 0 writes the images.
#include <sched.h>

#include <cstdio>
#include <map>
#include <optional>
#include <set>
#include <thread>

#include <fmt/core.h>

#include "cli/render_jobs.h"
#include "core/camera_path.h"
#include "core/error.h"
#include "io/mesh_framing.h"
#include "mpi/distributed_render.h"
#include "render/frame_parts.h"

namespace wideray::cli {
namespace {

/// One frame of the batch. Every rank lists the same frames, from the same files.
struct FrameJob {
    size_t scene = 0;  ///< in RenderArgs::scenes
    std::optional<int> frame;
    std::string error;  ///< the scene's frames could not be read: rendering it fails with this
};

std::vector<FrameJob> frameJobs(const RenderArgs& args) {
    std::vector<FrameJob> jobs;
    for (size_t s = 0; s < args.scenes.size(); ++s) {
        const std::string& file = args.scenes[s];
        try {
            const std::optional<FrameRange> range = sceneFileFrames(file);
            for (std::optional<int> frame : framesToRender(args, file, range)) jobs.push_back({s, frame, {}});
        } catch (const std::exception& e) {
            jobs.push_back({s, std::nullopt, e.what()});
        }
    }
    return jobs;
}

/// This rank's side of rendering items: the scene of the last item kept loaded for the next.
class PartRenderer {
public:
    PartRenderer(const RenderArgs& args, const std::vector<FrameJob>& jobs) : args_(args), jobs_(jobs) {}

    FramePart render(const WorkItem& item) {
        const FrameJob& job = jobs_.at(item.job);
        if (!job.error.empty()) throw std::runtime_error(job.error);
        if (const auto failed = loadErrors_.find(job.scene); failed != loadErrors_.end())
            throw std::runtime_error(failed->second);  // the scene's other frames: no second attempt
        double buildSeconds = 0;
        if (!loaded_ || loadedScene_ != job.scene) {
            loaded_.reset();
            try {
                loaded_ = loadForRender(args_, args_.scenes[job.scene]);
            } catch (const std::exception& e) {
                loadErrors_.emplace(job.scene, e.what());
                throw;
            }
            loadedScene_ = job.scene;
            buildSeconds = loaded_->buildSeconds;
        }
        SceneDescription& scene = loaded_->scene;
        if (job.frame) scene.camera = cameraAtFrame(*scene.animation, *job.frame);
        RenderOptions options = renderOptions(args_, "");
        options.progress = false;
        FramePart part = renderPart(scene, *loaded_->built.tracer, options, item);
        part.triangles = loaded_->geometry->triangleCount();
        part.accelName = loaded_->built.accelName;
        part.engine = loaded_->built.engine;
        part.buildSeconds = buildSeconds;
        return part;
    }

private:
    const RenderArgs& args_;
    const std::vector<FrameJob>& jobs_;
    std::optional<LoadedScene> loaded_;
    size_t loadedScene_ = 0;
    std::map<size_t, std::string> loadErrors_;  ///< by scene
};

/// mpirun binds each rank to one core when it starts at most 2 ranks, which leaves a rank's oneTBB
/// threads one core to share.
void warnIfBoundToOneCore() {
    cpu_set_t cpus;
    if (sched_getaffinity(0, sizeof(cpus), &cpus) != 0) return;
    if (CPU_COUNT(&cpus) == 1 && std::thread::hardware_concurrency() > 1)
        fmt::print(stderr, "warning: rank 0 may run on 1 of this machine's {} cores (mpirun binds ranks to cores by "
                           "default); pass --bind-to none to mpirun so that each rank's threads use them all\n",
                   std::thread::hardware_concurrency());
}

} // namespace

int renderWithMpi(const RenderArgs& args) {
    MpiSession session;
    if (args.compareBackends) {
        if (session.rank() == 0)
            fmt::print(stderr, "error: --compare-backends renders in one process; run it without mpirun\n");
        return 1;
    }
    if (session.rank() == 0) warnIfBoundToOneCore();
    const std::vector<FrameJob> jobs = frameJobs(args);
    PartRenderer renderer(args, jobs);
    std::map<size_t, std::set<std::string>> failures;  ///< messages by scene, each printed once
    const Aov aov = renderOptions(args, "").aov;

    DistributedBatch batch;
    batch.jobs = uint32_t(jobs.size());
    batch.progress = true;
    batch.renderPart = [&](const WorkItem& item) { return renderer.render(item); };
    batch.frameDone = [&](uint32_t j, Image&& image, const FrameSummary& summary) {
        const FrameJob& job = jobs[j];
        const std::string& file = args.scenes[job.scene];
        const FramePart& d = summary.description;
        FrameLine line{frameLabel(file, job.frame), d.width, d.height, d.samplesPerPixel, d.triangles,
                       d.accelName, d.engine, summary.slowestBuild, summary.stats, summary.ranks,
                       outputPath(args, file, job.frame)};
        writeFrame(image, line.output, aov);
        printFrameLine(line, aov);
    };
    batch.frameFailed = [&](uint32_t j, const std::string& message, int rank) {
        // The frames of a scene that does not load all fail alike: one line for them.
        if (!failures[jobs[j].scene].insert(message).second) return;
        fmt::print(stderr, "error: {} (rank {})\n", message, rank);
        std::fflush(stderr);
    };
    renderDistributed(session, batch);

    if (session.rank() != 0 || failures.empty()) return 0;
    fmt::print(stderr, "{} of {} scenes failed\n", failures.size(), args.scenes.size());
    return 1;
}

} // namespace wideray::cli
