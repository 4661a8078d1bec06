// Writing files so that a failure never damages what was there: a regular file (or a new one) is written
// to a temporary file in the same folder, flushed to disk and checked, then renamed over the target;
// FIFOs, devices and standard output are written directly, since they cannot be replaced.
#pragma once

#include <sys/types.h>

#include <cstdio>
#include <string>
#include <string_view>

#include "io/mesh_io.h"

namespace dbrg::io {

// A file written piece by piece with those guarantees, for output too large to hold: nothing is visible
// at the target until finish() succeeds, and a writer destroyed before that (or after a failed write)
// removes its temporary, leaving the file that was there untouched. Writes are buffered.
class FileWriter {
public:
    FileWriter() = default;
    ~FileWriter();
    FileWriter(const FileWriter&) = delete;
    FileWriter& operator=(const FileWriter&) = delete;

    // Starts writing `path` ("-" is standard output): refuses a folder or a file the user protected
    // against writing, and creates the temporary. Messages begin with the path and give the system's reason.
    IoStatus open(const std::string& path);
    // Appends `bytes`; the first failure is sticky and reported again by finish().
    IoStatus write(std::string_view bytes);
    // Flushes, fsyncs and renames the temporary over the target (a replaced file keeps its permission bits).
    IoStatus finish();
    // Gives up: removes the temporary (what a FIFO or standard output got stays).
    void abandon();

private:
    IoStatus write_out(std::string_view bytes);
    IoStatus flush();
    IoStatus fail(const char* action);

    static constexpr size_t BUFFER_BYTES = 1 << 20;
    std::string path_;       // as the caller named it, for messages
    std::string target_;     // where the rename goes (a symbolic link's file)
    std::string temporary_;  // empty when writing in place
    int descriptor_ = -1;
    FILE* stream_ = nullptr;  // standard output
    bool keep_mode_ = false;
    mode_t mode_ = 0;
    std::string buffer_;
    IoStatus status_;
};

// Writes `bytes` to `path` ("-" is standard output) with FileWriter's guarantees.
IoStatus write_file(const std::string& path, std::string_view bytes);

// Checks, before any work is done, that write_file could create `path`: its folder exists and accepts a
// new file (tried by creating and removing one), and it is not a folder. "-" is always writable.
IoStatus check_output_path(const std::string& path);

// True when both paths name one existing file (same device and inode), whatever their spelling.
bool same_file(const std::string& first, const std::string& second);

// The folder that holds `path` ("." for a bare name).
std::string folder_of(const std::string& path);

} // namespace dbrg::io
