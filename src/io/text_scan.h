// Line and token scanning and locale-independent number parsing shared by the text-format readers.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

namespace dbrg::io {

// Hands out the lines of a text one at a time ("\n" or "\r\n" endings), counting them from 1.
class LineReader {
public:
    explicit LineReader(std::string_view text) : rest_(text) {}

    // Stores the next line, without its ending, in `line`; returns false when the text is exhausted.
    bool next(std::string_view& line);
    // The number of the line `next` returned last.
    size_t line_number() const { return line_number_; }
    // Bytes not yet handed out.
    size_t remaining() const { return rest_.size(); }

private:
    std::string_view rest_;
    size_t line_number_ = 0;
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
    bool is_separator(char c) const;

    std::string_view rest_;
    bool comma_separates_;
};

// Tokens of a whole text regardless of line breaks, for formats that are a stream of values (ascii PLY).
class TokenStream {
public:
    explicit TokenStream(std::string_view text) : lines_(text) {}

    // Stores the next token in `token`; returns false at the end of the text.
    bool next(std::string_view& token);
    // The line of the token `next` returned last (or of the end of the text).
    size_t line_number() const { return lines_.line_number(); }
    // A generous upper bound on the tokens left: used to cap reservations driven by header counts.
    size_t remaining_bytes() const { return splitter_.remaining() + lines_.remaining(); }

private:
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
