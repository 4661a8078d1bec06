// A minimal writer for JSON objects with one member per line, for reports and statistics.
#pragma once

#include <charconv>
#include <cmath>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace dbrg::io {

// Builds `{ "key": value, ... }` in insertion order. Keys and strings are escaped; non-finite numbers,
// which JSON cannot express, are written as null.
class JsonObject {
public:
    JsonObject& add_unsigned(std::string_view key, uint64_t value) { return add_scalar(key, number_text(value)); }
    JsonObject& add_integer(std::string_view key, int64_t value) { return add_scalar(key, number_text(value)); }
    JsonObject& add_number(std::string_view key, double value) {
        if (!std::isfinite(value)) return add_null(key);
        return add_scalar(key, number_text(value));
    }
    JsonObject& add_bool(std::string_view key, bool value) { return add_scalar(key, value ? "true" : "false"); }
    JsonObject& add_null(std::string_view key) { return add_scalar(key, "null"); }
    JsonObject& add_string(std::string_view key, std::string_view value) { return add_scalar(key, quoted(value)); }
    JsonObject& add_object(std::string_view key, const JsonObject& value) {
        members_.push_back({quoted(key), std::string(), value.members_});
        return *this;
    }

    // The object's text, nested objects indented; ends without a newline.
    std::string str() const { return render(members_, 0); }

    static std::string quoted(std::string_view text) {
        std::string out = "\"";
        for (char c : text) {
            const unsigned char byte = static_cast<unsigned char>(c);
            if (c == '"' || c == '\\') {
                out.push_back('\\');
                out.push_back(c);
            } else if (byte < 0x20) {
                const char* hex = "0123456789abcdef";
                out += "\\u00";
                out.push_back(hex[byte >> 4]);
                out.push_back(hex[byte & 15]);
            } else {
                out.push_back(c);
            }
        }
        out.push_back('"');
        return out;
    }

private:
    struct Member {
        std::string key;                // already quoted
        std::string scalar;             // the value's text, unless the value is an object
        std::vector<Member> object;     // the members of an object value
    };

    template <class Number>
    static std::string number_text(Number value) {
        char text[32];
        const auto result = std::to_chars(text, text + sizeof text, value);
        return std::string(text, result.ptr);
    }
    JsonObject& add_scalar(std::string_view key, std::string value) {
        members_.push_back({quoted(key), std::move(value), {}});
        return *this;
    }
    static std::string render(const std::vector<Member>& members, size_t depth) {
        if (members.empty()) return "{}";
        const std::string indent(2 * (depth + 1), ' ');
        std::string text = "{\n";
        for (size_t i = 0; i < members.size(); ++i) {
            const Member& member = members[i];
            text += indent + member.key + ": ";
            text += member.scalar.empty() ? render(member.object, depth + 1) : member.scalar;
            text += i + 1 < members.size() ? ",\n" : "\n";
        }
        return text + std::string(2 * depth, ' ') + "}";
    }

    std::vector<Member> members_;
};

} // namespace dbrg::io
