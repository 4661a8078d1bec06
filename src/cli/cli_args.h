// Command-line helpers shared by the subcommands: option parsing, exit codes, error lines, output files.
#pragma once

#include <stdint.h>

#include <map>
#include <string>
#include <vector>

#include "dbrg/dbrg.h"
#include "io/mesh_io.h"

namespace dbrg::cli {

const int EXIT_OK = 0;
const int EXIT_FAILED = 1;  // the command was understood but could not be carried out
const int EXIT_USAGE = 2;   // the command line is wrong

// Prints "dbrg: <message>" on stderr and returns `exit_code`.
int report_error(int exit_code, const std::string& message);

struct OptionSpec {
    const char* name;   // "--points"
    const char* alias;  // "-p", or nullptr
    bool takes_value;
};

struct ParsedArgs {
    std::vector<std::string> positional;
    std::map<std::string, std::string> values;  // by OptionSpec::name; flags map to ""
    bool help = false;                          // -h or --help was given

    bool has(const std::string& name) const { return values.count(name) > 0; }
    // The option's value, or `fallback` when it was not given.
    std::string value(const std::string& name, const std::string& fallback = "") const;
};

// Parses argv[1..argc-1] (argv[0] is the command name) against `options`. Accepts "--name value",
// "--name=value", "-h"/"--help", and "--" to end the options. Returns false with a message in `error`
// for an unknown option, a missing value, or an option given twice.
bool parse_args(int argc, char** argv, const std::vector<OptionSpec>& options, ParsedArgs& parsed, std::string& error);

// A finite number, the whole text; false otherwise.
bool parse_number(const std::string& text, double& value);
// A whole number in 0 .. 2^32 - 1, the whole text; false otherwise.
bool parse_count(const std::string& text, uint32_t& value);

// A size in bytes: a positive decimal number with an optional unit, in any letter case: K, M, G, T and
// KiB, MiB, GiB, TiB are powers of 1024 (1K is 1024 bytes), KB, MB, GB, TB powers of 1000 (as Dask reads
// them; Dask reads the single letters as powers of 1000 too), B bytes; the whole text ("1.5G", "2GiB"),
// the bytes rounded down; false otherwise.
bool parse_size(const std::string& text, uint64_t& bytes);

// Writes `text` to the file at `path` (a failed write leaves the old file untouched), or to stdout when
// path is empty or "-". Returns false with a message in `error` when the file cannot be written.
bool write_text_output(const std::string& path, const std::string& text, std::string& error);

// Reports a failed library call: "dbrg: STATUS: message", where a non-finite point also names its place in
// the input file (the library knows only the point's index; the reader knew where it was). Returns
// EXIT_FAILED.
int report_library_error(dbrg_status status, const char* message, const std::string& input, const io::MeshData& points);

// Checks, before any work, that each of `outputs` (empty and "-" are standard output) can be written and
// none is the file `input` (compared by device and inode, so other spellings of its path are caught too).
// Returns false with a message in `error` naming the first one that cannot.
bool check_outputs(const std::vector<std::string>& outputs, const std::string& input, std::string& error);

} // namespace dbrg::cli
