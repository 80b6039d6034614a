#pragma once
// Whether this process is one of the ranks that mpirun (or mpiexec) started, from the environment the
// launcher gives its processes, so that a plain `wideray render` never initializes MPI.
#include <algorithm>
#include <cstdlib>
#include <string>

namespace wideray {

/// The number of processes the launcher started (OpenMPI, or a PMI launcher such as MPICH's Hydra);
/// 0 when this process was not started by one.
inline int launchedRanks() {
    for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_SIZE"})
        if (const char* value = std::getenv(name)) return std::max(1, std::atoi(value));
    if (std::getenv("PMIX_RANK")) return 1;
    return 0;
}

} // namespace wideray
