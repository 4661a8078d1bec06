// Writing whole files so that a failure never damages what was there: a regular file (or a new one) is
// written to a temporary file in the same folder, flushed to disk and checked, then renamed over the
// target; FIFOs, devices and standard output are written directly, since they cannot be replaced.
#pragma once

#include <string>
#include <string_view>

#include "io/mesh_io.h"

namespace dbrg::io {

// Writes `bytes` to `path` ("-" is standard output). A replaced file keeps its permission bits. On
// failure the file that was there is untouched, no temporary is left behind, and the message begins with
// the path and gives the system's reason.
IoStatus write_file(const std::string& path, std::string_view bytes);

// Checks, before any work is done, that write_file could create `path`: its folder exists and accepts a
// new file (tried by creating and removing one), and it is not a folder. "-" is always writable.
IoStatus check_output_path(const std::string& path);

// True when both paths name one existing file (same device and inode), whatever their spelling.
bool same_file(const std::string& first, const std::string& second);

} // namespace dbrg::io
