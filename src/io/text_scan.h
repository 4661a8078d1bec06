// Line and token scanning and locale-independent number parsing shared by the text-format readers.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "io/byte_source.h"

namespace dbrg::io {

// Space, tab, CR, form feed or vertical tab. Inline: it is asked of every byte of a text file.
inline bool is_blank(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v'; }

// Hands out the lines of a text one at a time ("\n" or "\r\n" endings), counting them from 1, pulling the
// text from a ByteSource as it goes. A line holding a zero byte, or longer than the limit, stops the
// text with an error: that is binary data or garbage, and is refused as soon as it arrives instead of
// being buffered until a line break that may never come.
class LineReader {
public:
    // No text format needs longer lines (an OBJ face of a million corners takes about 8 MiB).
    static constexpr size_t DEFAULT_MAX_LINE_BYTES = 16 << 20;

    explicit LineReader(ByteSource& source, size_t max_line_bytes = DEFAULT_MAX_LINE_BYTES)
        : source_(source), max_line_bytes_(max_line_bytes) {}

    // Stores the next line, without its ending, in `line` (valid until the next call); returns false
    // when the text is exhausted or refused (then error() says why).
    bool next(std::string_view& line);
    // The number of the line `next` returned or refused last.
    size_t line_number() const { return line_number_; }
    // Why the text was refused; empty when it simply ended.
    const std::string& error() const { return error_; }
    bool failed() const { return !error_.empty(); }
    // The error, or `at_end` when the text simply ended: for readers that needed more lines.
    std::string stop_reason(const std::string& at_end) const { return failed() ? error_ : at_end; }

private:
    static constexpr uint64_t NO_ZERO = UINT64_MAX;
    static constexpr size_t ZERO_SEARCH_AHEAD = 64 << 10;

    // Whether the first `length` bytes of the line at the start of `window` hold a zero byte.
    bool holds_zero(std::string_view window, size_t length);
    bool refuse(std::string why);

    ByteSource& source_;
    size_t max_line_bytes_;
    size_t line_number_ = 0;
    uint64_t clean_until_ = 0;    // searched from the current line up to this offset: no zero byte
    uint64_t zero_at_ = NO_ZERO;  // the zero byte that ended the search, if one did
    std::string error_;
};

// Splits one line into tokens separated by blanks (space, tab, CR, form feed, vertical tab) and, when
// asked, commas.
class TokenSplitter {
public:
    explicit TokenSplitter(std::string_view line, bool comma_separates = false)
        : rest_(line), comma_separates_(comma_separates) {}

    // Stores the next token in `token`; returns false when the line has no more.
    bool next(std::string_view& token);
    // Bytes of the line not yet handed out.
    size_t remaining() const { return rest_.size(); }

private:
    bool is_separator(char c) const { return is_blank(c) || (comma_separates_ && c == ','); }

    std::string_view rest_;
    bool comma_separates_;
};

// Tokens of a whole text regardless of line breaks, for formats that are a stream of values (ascii PLY).
class TokenStream {
public:
    explicit TokenStream(ByteSource& source) : source_(source), lines_(source) {}

    // Stores the next token in `token` (valid until the next call); returns false at the end of the text
    // or when a line is refused (then error() says why).
    bool next(std::string_view& token);
    // The line of the token `next` returned last (or of the end of the text, or of a refused line).
    size_t line_number() const { return lines_.line_number(); }
    const std::string& error() const { return lines_.error(); }
    // The bytes not handed out yet, when the input's size is known: a generous upper bound on the
    // tokens left, used to cap counts from a header.
    std::optional<uint64_t> bytes_left() const;

private:
    ByteSource& source_;
    LineReader lines_;
    TokenSplitter splitter_{std::string_view()};
};

// Parses the whole token as a decimal floating-point number (an optional leading '+' is accepted, as are
// "inf" and "nan"). Never consults the locale.
bool parse_double(std::string_view token, double& value);

// Parses the whole token as a decimal integer with an optional sign.
bool parse_int64(std::string_view token, int64_t& value);

// The text without leading and trailing blanks.
std::string_view strip_blanks(std::string_view text);

// The line without everything from the first `marker` on.
std::string_view strip_comment(std::string_view line, char marker = '#');

// The token in single quotes for an error message, shortened when it is long.
std::string quote_token(std::string_view token);

} // namespace dbrg::io
