// The C++ side of scripts/library_bench.py: the same rays through the public API (the shared library)
// as the Python path traces from numpy, so that the two rates compare the bindings' cost alone.
//   wideray_library_bench MESH RAYS RUNS   (RAYS: float32 ox oy oz dx dy dz per ray)
// prints {"rays": N, "seconds": [...], "build_seconds": S} on one line.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include <wideray/wideray.h>

int main(int argc, char** argv) {
    if (argc != 4) {
        std::fprintf(stderr, "usage: %s MESH RAYS RUNS\n", argv[0]);
        return 2;
    }
    using Clock = std::chrono::steady_clock;
    try {
        const wideray::MeshArrays mesh = wideray::loadMeshFile(argv[1]);
        std::ifstream in(argv[2], std::ios::binary | std::ios::ate);
        if (!in) throw wideray::Error(std::string(argv[2]) + ": cannot read");
        std::vector<float> values(size_t(in.tellg()) / sizeof(float));
        in.seekg(0);
        in.read(reinterpret_cast<char*>(values.data()), std::streamsize(values.size() * sizeof(float)));
        const int runs = std::max(1, std::stoi(argv[3]));

        const auto start = Clock::now();
        wideray::Scene scene;
        scene.addTriangleMesh(mesh.positions, mesh.indices, wideray::Sharing::Shared);
        scene.build();
        const double buildSeconds = std::chrono::duration<double>(Clock::now() - start).count();

        std::vector<wideray::Ray> rays(values.size() / 6);
        for (size_t i = 0; i < rays.size(); ++i) {
            const float* v = &values[6 * i];
            rays[i] = {v[0], v[1], v[2], v[3], v[4], v[5]};
        }
        std::vector<wideray::Hit> hits(rays.size());
        std::string seconds;
        for (int r = 0; r <= runs; ++r) {  // one warm-up
            const auto t0 = Clock::now();
            scene.intersect(rays, hits, wideray::Coherence::Incoherent, wideray::Threading::Parallel);
            const double s = std::chrono::duration<double>(Clock::now() - t0).count();
            if (r > 0) seconds += (seconds.empty() ? "" : ", ") + std::to_string(s);
        }
        std::printf("{\"rays\": %zu, \"seconds\": [%s], \"build_seconds\": %f}\n", rays.size(), seconds.c_str(),
                    buildSeconds);
        return 0;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "error: %s\n", e.what());
        return 1;
    }
}
