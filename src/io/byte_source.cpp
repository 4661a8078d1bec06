// The bytes a reader parses, made available a piece at a time (see byte_source.h).
#include "io/byte_source.h"

#include <algorithm>
#include <cstring>
#include <utility>

namespace dbrg::io {

ByteSource::ByteSource(std::string_view bytes)
    : total_bytes_(bytes.size()), data_(bytes.data()), end_(bytes.size()), ended_(true) {}

ByteSource::ByteSource(Pull pull, std::optional<uint64_t> total_bytes, size_t chunk_bytes)
    : pull_(std::move(pull)), total_bytes_(total_bytes), buffer_(std::max<size_t>(chunk_bytes, 1)) {
    data_ = buffer_.data();
}

bool ByteSource::fill() {
    if (ended_) return false;
    const size_t kept = end_ - begin_;
    if (begin_ > 0) {
        std::memmove(buffer_.data(), buffer_.data() + begin_, kept);
        dropped_ += begin_;
        begin_ = 0;
        end_ = kept;
    }
    // A window longer than half the buffer (a long line, a large value) doubles it, so every pull still
    // asks for at least half a buffer and a long window is moved a logarithmic number of times.
    if (kept > buffer_.size() / 2) buffer_.resize(2 * buffer_.size());
    data_ = buffer_.data();
    const size_t got = pull_(buffer_.data() + end_, buffer_.size() - end_);
    if (got == 0) {
        ended_ = true;
        return false;
    }
    end_ += got;
    return true;
}

bool ByteSource::skip(uint64_t count) {
    for (;;) {
        const size_t step = static_cast<size_t>(std::min<uint64_t>(count, end_ - begin_));
        consume(step);
        count -= step;
        if (count == 0) return true;
        if (!fill()) return false;
    }
}

std::optional<uint64_t> ByteSource::bytes_left() const {
    if (!total_bytes_) return std::nullopt;
    // A file that shrank while being read has nothing left rather than a negative amount.
    return *total_bytes_ > offset() ? *total_bytes_ - offset() : 0;
}

} // namespace dbrg::io
