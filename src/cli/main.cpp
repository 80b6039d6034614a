// wideray: a thin command line over the engine. Each subcommand lives in its own file.
#include <cstdio>

#include "cli/commands.h"

int main(int argc, char** argv) {
    CLI::App app{"wideray: a wide-BVH ray tracing engine for multicore CPUs.\n"
                 "Run 'wideray COMMAND --help' for the options of a command."};
    app.require_subcommand(1);
    int exitCode = 0;
    wideray::cli::addRenderCommand(app, exitCode);
    wideray::cli::addInfoCommand(app, exitCode);
    wideray::cli::addBenchCommand(app, exitCode);
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        return app.exit(e);
    }
    return exitCode;
}
