// Line and token scanning and locale-independent number parsing shared by the text-format readers.
#include "io/text_scan.h"

#include <charconv>
#include <cstring>

namespace dbrg::io {
namespace {

bool is_blank(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v'; }

} // namespace

bool LineReader::next(std::string_view& line) {
    if (rest_.empty()) return false;
    const void* newline = std::memchr(rest_.data(), '\n', rest_.size());
    const size_t length = newline ? static_cast<size_t>(static_cast<const char*>(newline) - rest_.data())
                                  : rest_.size();
    line = rest_.substr(0, length);
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    rest_.remove_prefix(newline ? length + 1 : length);
    ++line_number_;
    return true;
}

bool TokenSplitter::is_separator(char c) const {
    return is_blank(c) || (comma_separates_ && c == ',');
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
