// Whole-file output that replaces a regular file only once the new contents are safely on disk.
#include "io/file_output.h"

#include <cerrno>
#include <climits>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

namespace dbrg::io {
namespace {

IoStatus failure(const std::string& path, const std::string& what) { return IoStatus::failure(path + ": " + what); }

IoStatus system_failure(const std::string& path, const char* action) {
    return failure(path, std::string(action) + ": " + std::strerror(errno));
}

// The folder that holds `path` ("." for a bare name), where the temporary file must go for the rename
// to be atomic.
std::string folder_of(const std::string& path) {
    const size_t slash = path.find_last_of('/');
    if (slash == std::string::npos) return ".";
    return slash == 0 ? "/" : path.substr(0, slash);
}

std::string name_of(const std::string& path) {
    const size_t slash = path.find_last_of('/');
    return slash == std::string::npos ? path : path.substr(slash + 1);
}

// A regular file is replaced where it really is, so a symbolic link to it stays a link.
std::string resolved(const std::string& path) {
    char real[PATH_MAX];
    return realpath(path.c_str(), real) ? std::string(real) : path;
}

// Creates a new, empty file beside `target` that nothing else uses; returns its descriptor (-1 with
// errno set on failure) and its name in `temporary`. Names carry the process id and an attempt number,
// and O_EXCL makes two writers in one process step past each other.
int create_temporary(const std::string& target, std::string& temporary) {
    const std::string stem = folder_of(target) + "/." + name_of(target) + ".dbrg-" + std::to_string(getpid()) + "-";
    for (int attempt = 0; attempt < 1000; ++attempt) {
        temporary = stem + std::to_string(attempt);
        const int descriptor = open(temporary.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
        if (descriptor >= 0 || errno != EEXIST) return descriptor;
    }
    errno = EEXIST;
    return -1;
}

bool write_all(int descriptor, std::string_view bytes) {
    while (!bytes.empty()) {
        const ssize_t written = write(descriptor, bytes.data(), bytes.size());
        if (written < 0 && errno == EINTR) continue;
        if (written <= 0) return false;
        bytes.remove_prefix(static_cast<size_t>(written));
    }
    return true;
}

IoStatus write_standard_output(std::string_view bytes) {
    const bool written = std::fwrite(bytes.data(), 1, bytes.size(), stdout) == bytes.size();
    if (written && std::fflush(stdout) == 0) return IoStatus::success();
    return system_failure("standard output", "cannot write");
}

// FIFOs and devices cannot be replaced by a rename: they get the bytes as they are.
IoStatus write_in_place(const std::string& path, std::string_view bytes) {
    const int descriptor = open(path.c_str(), O_WRONLY | O_TRUNC | O_CLOEXEC);
    if (descriptor < 0) return system_failure(path, "cannot open");
    const bool written = write_all(descriptor, bytes);
    const int saved_errno = errno;
    if (close(descriptor) != 0 || !written) {
        if (!written) errno = saved_errno;
        return system_failure(path, "cannot write");
    }
    return IoStatus::success();
}

// The whole contents to a temporary beside `target`, then one rename; the target is never half written.
IoStatus replace_atomically(const std::string& path, const std::string& target, const struct stat* old_file,
                            std::string_view bytes) {
    std::string temporary;
    const int descriptor = create_temporary(target, temporary);
    if (descriptor < 0) return system_failure(path, "cannot create a file in its folder");
    // fsync before the rename: a full disk often shows only when the data is flushed, and the old file
    // must not be replaced by one the disk never took.
    bool ok = write_all(descriptor, bytes) && (!old_file || fchmod(descriptor, old_file->st_mode & 07777) == 0) &&
              fsync(descriptor) == 0;
    int saved_errno = errno;
    if (close(descriptor) != 0 && ok) {
        ok = false;
        saved_errno = errno;
    }
    if (ok && rename(temporary.c_str(), target.c_str()) == 0) return IoStatus::success();
    if (ok) saved_errno = errno;
    unlink(temporary.c_str());
    errno = saved_errno;
    return system_failure(path, "cannot write");
}

// What stands at `path` now: found (with its stat) or not; a folder, or a file the user protected
// against writing, is refused.
IoStatus inspect_target(const std::string& path, bool& exists, struct stat& info) {
    exists = stat(path.c_str(), &info) == 0;
    if (!exists && errno != ENOENT) return system_failure(path, "cannot write");
    if (exists && S_ISDIR(info.st_mode)) return failure(path, "is a folder, not a file");
    if (exists && access(path.c_str(), W_OK) != 0) return system_failure(path, "cannot write");
    return IoStatus::success();
}

} // namespace

IoStatus write_file(const std::string& path, std::string_view bytes) {
    if (path == "-") return write_standard_output(bytes);
    bool exists = false;
    struct stat info;
    const IoStatus target_status = inspect_target(path, exists, info);
    if (!target_status) return target_status;
    if (exists && !S_ISREG(info.st_mode)) return write_in_place(path, bytes);
    return exists ? replace_atomically(path, resolved(path), &info, bytes) : replace_atomically(path, path, nullptr, bytes);
}

IoStatus check_output_path(const std::string& path) {
    if (path == "-") return IoStatus::success();
    bool exists = false;
    struct stat info;
    const IoStatus target_status = inspect_target(path, exists, info);
    if (!target_status || (exists && !S_ISREG(info.st_mode))) return target_status;
    std::string temporary;
    const int descriptor = create_temporary(exists ? resolved(path) : path, temporary);
    if (descriptor < 0) return system_failure(path, "cannot create a file in its folder");
    close(descriptor);
    unlink(temporary.c_str());
    return IoStatus::success();
}

bool same_file(const std::string& first, const std::string& second) {
    struct stat a, b;
    return stat(first.c_str(), &a) == 0 && stat(second.c_str(), &b) == 0 && a.st_dev == b.st_dev && a.st_ino == b.st_ino;
}

} // namespace dbrg::io
