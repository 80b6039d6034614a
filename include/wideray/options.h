#pragma once
/// How a scene is built and traced: build quality, BVH width, a forced kernel or ISA; instance
/// transforms; what happens to the caller's arrays; who traces a batch.
#include <string>

namespace wideray {

enum class BuildQuality {
    Fast,  ///< binned SAH over whole triangles: the quick build
    High,  ///< spatial splits too (SBVH): slower to build, faster to trace where triangles are long
};

struct SceneOptions {
    BuildQuality quality = BuildQuality::Fast;
    int bvhWidth = 8;  ///< children per node: 4, 8 or 16
    /// A kernel for every call ("scalar", "single", "packet4", "packet8", "packet16", "packet256",
    /// "stream", "drst"); empty: the fastest for each kind of call. For tests and measurements.
    std::string kernel;
    /// The instruction set ("sse42", "avx2", "avx512"); empty: the best this CPU runs.
    std::string isa;
};

/// An affine object-to-world transform, row-major: world = m * (x, y, z, 1).
struct Transform {
    float m[3][4] = {{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}};
};

/// What addTriangleMesh does with the caller's arrays.
enum class Sharing {
    Copy,    ///< copied at once; the caller may free them when the call returns
    Shared,  ///< not copied but read by every build(): keep them alive until the scene's last build()
};

/// Who traces a batch of rays.
enum class Threading {
    Caller,    ///< the calling thread alone
    Parallel,  ///< wideray's worker threads (oneTBB) share it; the call returns when all are done
};

} // namespace wideray
