#pragma once
// The subcommands of the wideray executable.
#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "backends/structure.h"
#include "geometry/instance_geometry.h"

namespace wideray::cli {

/// Options of render: threads, the kernel and its ISA, the BVH's width and build quality.
struct EngineOptions {
    int threads = 0;  ///< 0: all hardware threads
    std::string kernel = "auto";
    std::string isa = "auto";
    std::string accel;  ///< empty: the wide BVH of bvhWidth
    int bvhWidth = 8;
    std::string quality = "fast";
    std::string shadowCache = "on";
    std::string instancing = "auto";
};

void addEngineOptions(CLI::App& app, EngineOptions& options);
/// --quality fast|high.
void addQualityOption(CLI::App& app, std::string& quality);
/// The --accel choices (backends/accel_registry.h's rows) and their help, for one name or a list.
std::vector<std::string> accelNames();
/// The names of our wide BVHs (the rows with Accel::wideBvh), info's default.
std::vector<std::string> wideBvhNames();
std::string accelHelp(bool list);
/// --instancing auto|flatten|two-level.
void addInstancingOption(CLI::App& app, std::string& instancing);
/// The instancing the option asks for, for structures `accels` (empty: the wide BVH): auto flattens
/// for the course's structures, which are single-level; two-level with one of them is an error.
Instancing instancingFor(const std::string& option, const std::vector<std::string>& accels);
/// The kernels the options ask for.
KernelChoice kernelChoice(const EngineOptions& options);

void addRenderCommand(CLI::App& app, int& exitCode);
void addInfoCommand(CLI::App& app, int& exitCode);
void addBenchCommand(CLI::App& app, int& exitCode);

/// Parses "WxH" (e.g. 1024x768); throws CLI::ValidationError.
std::pair<int, int> parseSize(const std::string& text);

} // namespace wideray::cli
