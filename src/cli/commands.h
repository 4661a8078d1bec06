// The subcommands of the dbrg program, one source file each (command_<name>.cpp).
#pragma once

namespace dbrg::cli {

// Each takes the arguments that follow the program name, the command's own name first
// (argv[0] is "stats"), and returns the process exit code.
int run_stats(int argc, char** argv);
int run_reconstruct(int argc, char** argv);
int run_delaunay(int argc, char** argv);

} // namespace dbrg::cli
