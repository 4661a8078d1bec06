// File output that replaces a regular file only once the new contents are safely on disk.
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

// The temporary goes in the target's folder, where the rename is atomic.
std::string folder_of(const std::string& path) {
    const size_t slash = path.find_last_of('/');
    if (slash == std::string::npos) return ".";
    return slash == 0 ? "/" : path.substr(0, slash);
}

FileWriter::~FileWriter() { abandon(); }

void FileWriter::abandon() {
    if (descriptor_ >= 0) close(descriptor_);
    descriptor_ = -1;
    if (!temporary_.empty()) unlink(temporary_.c_str());
    temporary_.clear();
    stream_ = nullptr;
}

IoStatus FileWriter::fail(const char* action) {
    const int saved_errno = errno;
    abandon();
    errno = saved_errno;
    status_ = system_failure(path_ == "-" ? "standard output" : path_, action);
    return status_;
}

IoStatus FileWriter::open(const std::string& path) {
    abandon();
    path_ = path;
    status_ = IoStatus::success();
    buffer_.clear();
    buffer_.reserve(BUFFER_BYTES);
    if (path == "-") {
        stream_ = stdout;
        return status_;
    }
    bool exists = false;
    struct stat info;
    status_ = inspect_target(path, exists, info);
    if (!status_) return status_;
    if (exists && !S_ISREG(info.st_mode)) {
        // FIFOs and devices cannot be replaced by a rename: they get the bytes as they come.
        descriptor_ = ::open(path.c_str(), O_WRONLY | O_TRUNC | O_CLOEXEC);
        return descriptor_ < 0 ? fail("cannot open") : status_;
    }
    target_ = exists ? resolved(path) : path;
    keep_mode_ = exists;
    mode_ = exists ? info.st_mode & 07777 : 0;
    descriptor_ = create_temporary(target_, temporary_);
    if (descriptor_ < 0) {
        temporary_.clear();
        return fail("cannot create a file in its folder");
    }
    return status_;
}

IoStatus FileWriter::write_out(std::string_view bytes) {
    if (!status_ || bytes.empty()) return status_;
    const bool written = stream_ ? std::fwrite(bytes.data(), 1, bytes.size(), stream_) == bytes.size()
                                 : write_all(descriptor_, bytes);
    return written ? status_ : fail("cannot write");
}

IoStatus FileWriter::flush() {
    write_out(buffer_);
    buffer_.clear();
    return status_;
}

IoStatus FileWriter::write(std::string_view bytes) {
    if (buffer_.size() + bytes.size() > BUFFER_BYTES && !flush()) return status_;
    // A large piece (a whole mesh) goes out as it is rather than through the buffer.
    if (bytes.size() >= BUFFER_BYTES) return write_out(bytes);
    if (status_) buffer_.append(bytes.data(), bytes.size());
    return status_;
}

IoStatus FileWriter::finish() {
    if (!flush()) return status_;
    if (stream_) {
        const bool flushed = std::fflush(stream_) == 0;
        stream_ = nullptr;
        return flushed ? status_ : fail("cannot write");
    }
    if (temporary_.empty()) {
        const int descriptor = descriptor_;
        descriptor_ = -1;
        return close(descriptor) == 0 ? status_ : fail("cannot write");
    }
    // fsync before the rename: a full disk often shows only when the data is flushed, and the old file
    // must not be replaced by one the disk never took.
    if ((keep_mode_ && fchmod(descriptor_, mode_) != 0) || fsync(descriptor_) != 0) return fail("cannot write");
    const int descriptor = descriptor_;
    descriptor_ = -1;
    if (close(descriptor) != 0 || rename(temporary_.c_str(), target_.c_str()) != 0) return fail("cannot write");
    temporary_.clear();
    return status_;
}

IoStatus write_file(const std::string& path, std::string_view bytes) {
    FileWriter writer;
    IoStatus status = writer.open(path);
    if (status) status = writer.write(bytes);
    return status ? writer.finish() : status;
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
