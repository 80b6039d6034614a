#pragma once
// The subcommands of the wideray executable.
#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "backends/structure.h"

namespace wideray::cli {

/// Options shared by render and bench: threads, the kernel and its ISA, the BVH width.
struct EngineOptions {
    int threads = 0;  ///< 0: all hardware threads
    std::string kernel = "auto";
    std::string isa = "auto";
    int bvhWidth = 8;
    std::string shadowCache = "on";
};

void addEngineOptions(CLI::App& app, EngineOptions& options);
/// The kernels the options ask for.
KernelChoice kernelChoice(const EngineOptions& options);

void addRenderCommand(CLI::App& app, int& exitCode);
void addInfoCommand(CLI::App& app, int& exitCode);
void addBenchCommand(CLI::App& app, int& exitCode);

/// Parses "WxH" (e.g. 1024x768); throws CLI::ValidationError.
std::pair<int, int> parseSize(const std::string& text);

} // namespace wideray::cli
