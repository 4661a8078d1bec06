// The bytes a reader parses, made available a piece at a time: all of an in-memory buffer at once, or a
// file or pipe pulled in chunks, so that memory follows what has been parsed rather than what is offered.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <string_view>
#include <vector>

namespace dbrg::io {

class ByteSource {
public:
    // Writes up to `capacity` bytes to `destination` and returns how many; 0 at the end of the input.
    using Pull = std::function<size_t(char* destination, size_t capacity)>;

    // Large enough that a refill costs little next to parsing it, small enough to stay in cache.
    static constexpr size_t DEFAULT_CHUNK_BYTES = 256 << 10;

    // All of `bytes` at once; they must outlive the source.
    explicit ByteSource(std::string_view bytes);
    // Bytes from `pull`, `chunk_bytes` or more at a time. `total_bytes` is the input's size when it is
    // known beforehand (a regular file), which lets readers check a header's counts against it.
    ByteSource(Pull pull, std::optional<uint64_t> total_bytes, size_t chunk_bytes = DEFAULT_CHUNK_BYTES);

    // The bytes read in and not consumed yet; valid until the next fill (ensure and skip may fill).
    std::string_view window() const { return {data_ + begin_, end_ - begin_}; }
    // Drops the first `count` bytes of the window (count <= window().size()).
    void consume(size_t count) { begin_ += count; }
    // Reads more input onto the end of the window; false at the end of the input. The window's bytes
    // stay, but may move, even when it returns false.
    bool fill();
    // Fills until the window holds at least `count` bytes; false when the input ends first.
    bool ensure(size_t count) {
        while (end_ - begin_ < count) {
            if (!fill()) return false;
        }
        return true;
    }
    // Consumes `count` bytes, filling as needed; false, with everything consumed, when the input ends first.
    bool skip(uint64_t count);
    // The position of the window's first byte in the input.
    uint64_t offset() const { return dropped_ + begin_; }
    // The bytes not consumed yet, when the input's size is known.
    std::optional<uint64_t> bytes_left() const;
    bool size_known() const { return total_bytes_.has_value(); }

private:
    Pull pull_;
    std::optional<uint64_t> total_bytes_;
    std::vector<char> buffer_;  // the window of a pulled input, with room for the next chunk
    const char* data_ = nullptr;
    size_t begin_ = 0;
    size_t end_ = 0;
    uint64_t dropped_ = 0;  // bytes moved out of the buffer by earlier fills
    bool ended_ = false;
};

} // namespace dbrg::io
