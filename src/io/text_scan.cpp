// Line and token scanning and locale-independent number parsing shared by the text-format readers.
#include "io/text_scan.h"

#include <algorithm>
#include <charconv>
#include <cstring>
#include <utility>

namespace dbrg::io {
namespace {

// The first `byte` of text[from, to), or nullptr; memchr without its undefined case of a null pointer.
const char* find_byte(std::string_view text, size_t from, size_t to, char byte) {
    return from < to ? static_cast<const char*>(std::memchr(text.data() + from, byte, to - from)) : nullptr;
}

} // namespace

bool LineReader::next(std::string_view& line) {
    if (failed()) return false;
    // The line grows over fills until its break turns up. Only a zero byte among its first
    // max_line_bytes_ bytes counts, so a buffer read at once and one read in chunks fail alike.
    size_t searched = 0;  // bytes of the line known to hold no line break
    size_t seen = 0;      // bytes of the line in the window
    const char* newline = nullptr;
    std::string_view window = source_.window();
    for (;;) {
        newline = find_byte(window, searched, window.size(), '\n');
        seen = newline ? static_cast<size_t>(newline - window.data()) : window.size();
        const size_t to_check = std::min(seen, max_line_bytes_);
        if (holds_zero(window, to_check)) return refuse("binary data (a zero byte) where text was expected");
        if (seen > max_line_bytes_) {
            return refuse("a line longer than " + std::to_string(max_line_bytes_) + " bytes, the most this reader accepts");
        }
        if (newline) break;
        const bool filled = source_.fill();
        window = source_.window();  // moved by any fill, even one that finds the end
        if (!filled) break;
        searched = seen;
    }
    if (window.empty()) return false;
    line = window.substr(0, seen);
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    source_.consume(newline ? seen + 1 : seen);
    ++line_number_;
    return true;
}

bool LineReader::holds_zero(std::string_view window, size_t length) {
    const uint64_t start = source_.offset();
    const uint64_t end = start + length;
    if (end > clean_until_ && zero_at_ == NO_ZERO) {
        // One search runs ahead of the line to serve the lines after it (a call per line would cost 5%
        // of reading an XYZ file), but not far: the text may end where binary data begins (a PLY header).
        const size_t from = static_cast<size_t>(std::max(clean_until_, start) - start);
        const size_t to = std::min(window.size(), length + ZERO_SEARCH_AHEAD);
        const char* zero = find_byte(window, from, to, '\0');
        zero_at_ = zero ? start + static_cast<uint64_t>(zero - window.data()) : NO_ZERO;
        clean_until_ = zero ? zero_at_ : start + to;
    }
    return zero_at_ < end;
}

bool LineReader::refuse(std::string why) {
    ++line_number_;
    error_ = std::move(why);
    return false;
}

bool TokenSplitter::next(std::string_view& token) {
    size_t begin = 0;
    while (begin < rest_.size() && is_separator(rest_[begin])) ++begin;
    if (begin == rest_.size()) {
        rest_ = std::string_view();
        return false;
    }
    size_t end = begin;
    while (end < rest_.size() && !is_separator(rest_[end])) ++end;
    token = rest_.substr(begin, end - begin);
    rest_.remove_prefix(end);
    return true;
}

bool TokenStream::next(std::string_view& token) {
    while (!splitter_.next(token)) {
        std::string_view line;
        if (!lines_.next(line)) return false;
        splitter_ = TokenSplitter(line);
    }
    return true;
}

std::optional<uint64_t> TokenStream::bytes_left() const {
    const std::optional<uint64_t> unread = source_.bytes_left();
    if (!unread) return std::nullopt;
    return *unread + splitter_.remaining();
}

namespace {

// The whole token as one number of type T, with an optional leading '+' (from_chars rejects it, but C's
// strtod and many writers produce it).
template <class T>
bool parse_whole(std::string_view token, T& value) {
    if (!token.empty() && token.front() == '+') {
        token.remove_prefix(1);
        if (!token.empty() && token.front() == '-') return false;
    }
    if (token.empty()) return false;
    const char* end = token.data() + token.size();
    const auto result = std::from_chars(token.data(), end, value);
    // Out-of-range values ("1e999") fail too: the reader names them rather than guess a value.
    return result.ec == std::errc() && result.ptr == end;
}

} // namespace

bool parse_double(std::string_view token, double& value) { return parse_whole(token, value); }

bool parse_int64(std::string_view token, int64_t& value) { return parse_whole(token, value); }

std::string_view strip_blanks(std::string_view text) {
    while (!text.empty() && is_blank(text.front())) text.remove_prefix(1);
    while (!text.empty() && is_blank(text.back())) text.remove_suffix(1);
    return text;
}

std::string_view strip_comment(std::string_view line, char marker) {
    const size_t at = line.find(marker);
    return at == std::string_view::npos ? line : line.substr(0, at);
}

std::string quote_token(std::string_view token) {
    const size_t limit = 40;
    std::string quoted = "'";
    if (token.size() > limit) {
        quoted.append(token.substr(0, limit));
        quoted += "...";
    } else {
        quoted.append(token);
    }
    // Binary garbage must not put control bytes on the user's terminal.
    for (char& c : quoted) {
        if (static_cast<unsigned char>(c) < 0x20 || static_cast<unsigned char>(c) >= 0x7f) c = '?';
    }
    quoted += "'";
    return quoted;
}

} // namespace dbrg::io
