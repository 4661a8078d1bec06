// The dbrg program: dispatches to its subcommands and answers --help and --version.
#include <cstdio>
#include <exception>
#include <new>
#include <string>

#include "cli/allocator_settings.h"
#include "cli/cli_args.h"
#include "cli/commands.h"
#include "dbrg/dbrg.h"

namespace {

using dbrg::cli::EXIT_OK;
using dbrg::cli::EXIT_USAGE;

struct Command {
    const char* name;
    int (*run)(int argc, char** argv);
    const char* synopsis;
};

const Command COMMANDS[] = {
    {"reconstruct", dbrg::cli::run_reconstruct, "INPUT -o OUTPUT [options]   reconstruct a surface from a point cloud"},
    {"delaunay", dbrg::cli::run_delaunay, "INPUT [options]              Delaunay tetrahedralization of a point cloud"},
    {"stats", dbrg::cli::run_stats, "MESH [--points INPUT]        JSON report on a triangle mesh"},
};

void print_usage(std::FILE* stream) {
    std::fputs("usage: dbrg <command> [arguments]\n"
               "\n"
               "Surface reconstruction from unorganized 3D points by Delaunay-based region growing.\n"
               "\n"
               "commands:\n",
               stream);
    for (const Command& command : COMMANDS) std::fprintf(stream, "  %-12s %s\n", command.name, command.synopsis);
    std::fputs("\n"
               "Run 'dbrg <command> --help' for the options of a command.\n"
               "  -h, --help     show this help\n"
               "  --version      print the version of the dbrg library\n",
               stream);
}

} // namespace

namespace {

int run(int argc, char** argv) {
    if (argc < 2) {
        print_usage(stderr);
        return EXIT_USAGE;
    }
    const std::string first = argv[1];
    if (first == "-h" || first == "--help" || first == "help") {
        print_usage(stdout);
        return EXIT_OK;
    }
    if (first == "--version") {
        std::printf("dbrg %s\n", dbrg_version_string());
        return EXIT_OK;
    }
    for (const Command& command : COMMANDS) {
        if (first != command.name) continue;
        return command.run(argc - 1, argv + 1);
    }
    return dbrg::cli::report_error(EXIT_USAGE, "unknown command '" + first + "' (see 'dbrg --help')");
}

} // namespace

// The library reports through statuses, but the program's own containers can still throw (a huge demo,
// a huge file): every way out of the program is a message and a non-zero exit, never an abort.
int main(int argc, char** argv) {
    dbrg::cli::keep_freed_blocks();
    try {
        return run(argc, argv);
    } catch (const std::bad_alloc&) {
        return dbrg::cli::report_error(dbrg::cli::EXIT_FAILED, "out of memory");
    } catch (const std::exception& error) {
        return dbrg::cli::report_error(dbrg::cli::EXIT_FAILED, std::string("unexpected error: ") + error.what());
    }
}
