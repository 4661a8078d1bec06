// Command-line helpers shared by the subcommands: option parsing, exit codes, error lines, output files.
#include "cli/cli_args.h"

#include <cctype>
#include <cmath>
#include <cstdlib>
#include <cstdio>
#include <cstring>

#include "cli/interrupt.h"
#include "io/file_output.h"

namespace dbrg::cli {

int report_error(int exit_code, const std::string& message) {
    // A call cancelled by Ctrl-C fails with whatever it was doing: say why it stopped instead.
    if (interrupted()) {
        std::fputs("dbrg: interrupted; no output written\n", stderr);
        return interrupted_exit_code();
    }
    std::fprintf(stderr, "dbrg: %s\n", message.c_str());
    return exit_code;
}

std::string ParsedArgs::value(const std::string& name, const std::string& fallback) const {
    const auto found = values.find(name);
    return found == values.end() ? fallback : found->second;
}

bool parse_args(int argc, char** argv, const std::vector<OptionSpec>& options, ParsedArgs& parsed, std::string& error) {
    bool options_ended = false;
    for (int i = 1; i < argc; ++i) {
        std::string word = argv[i];
        if (options_ended || word.size() < 2 || word[0] != '-') {
            parsed.positional.push_back(word);
            continue;
        }
        if (word == "--") {
            options_ended = true;
            continue;
        }
        if (word == "-h" || word == "--help") {
            parsed.help = true;
            continue;
        }
        std::string inline_value;
        bool has_inline_value = false;
        const size_t equals = word.find('=');
        if (word.compare(0, 2, "--") == 0 && equals != std::string::npos) {
            inline_value = word.substr(equals + 1);
            word.resize(equals);
            has_inline_value = true;
        }
        const OptionSpec* spec = nullptr;
        for (const OptionSpec& option : options) {
            if (word == option.name || (option.alias && word == option.alias)) spec = &option;
        }
        if (!spec) {
            error = "unknown option '" + word + "'";
            return false;
        }
        if (parsed.has(spec->name)) {
            error = "option '" + std::string(spec->name) + "' given twice";
            return false;
        }
        if (!spec->takes_value) {
            if (has_inline_value) {
                error = "option '" + word + "' takes no value";
                return false;
            }
            parsed.values[spec->name] = "";
        } else if (has_inline_value) {
            parsed.values[spec->name] = inline_value;
        } else if (i + 1 < argc) {
            parsed.values[spec->name] = argv[++i];
        } else {
            error = "option '" + word + "' needs a value";
            return false;
        }
    }
    return true;
}

bool write_text_output(const std::string& path, const std::string& text, std::string& error) {
    const io::IoStatus status = io::write_file(path.empty() ? "-" : path, text);
    if (!status) error = status.message;
    return status.ok;
}

int report_library_error(dbrg_status status, const char* message, const std::string& input, const io::MeshData& points) {
    std::string text = std::string(dbrg_status_string(status)) + ": " + message;
    if (status == DBRG_ERR_NON_FINITE_INPUT && !input.empty() && !points.non_finite_at.empty()) {
        text += " (" + input + " " + points.non_finite_at + ")";
    }
    return report_error(EXIT_FAILED, text);
}

bool check_outputs(const std::vector<std::string>& outputs, const std::string& input, std::string& error) {
    for (const std::string& output : outputs) {
        if (output.empty() || output == "-") continue;
        if (!input.empty() && io::same_file(output, input)) return error = output + ": is the input file; choose another output", false;
        const io::IoStatus status = io::check_output_path(output);
        if (!status) return error = status.message, false;
    }
    return true;
}

bool parse_number(const std::string& text, double& value) {
    char* end = nullptr;
    value = std::strtod(text.c_str(), &end);
    return !text.empty() && end == text.c_str() + text.size() && std::isfinite(value);
}

bool parse_count(const std::string& text, uint32_t& value) {
    double number;
    if (!parse_number(text, number) || number < 0 || number > 4294967295.0 || number != std::floor(number)) return false;
    value = uint32_t(number);
    return true;
}

bool parse_size(const std::string& text, uint64_t& bytes) {
    // Longer suffixes first: "kib" and "kb" end in "b" too.
    static const struct {
        const char* suffix;
        double factor;
    } UNITS[] = {{"kib", 0x1p10}, {"mib", 0x1p20}, {"gib", 0x1p30}, {"tib", 0x1p40}, {"kb", 1e3}, {"mb", 1e6},
                 {"gb", 1e9},     {"tb", 1e12},    {"k", 0x1p10},   {"m", 0x1p20},   {"g", 0x1p30}, {"t", 0x1p40},
                 {"b", 1}};
    std::string number = text;
    for (char& c : number) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    double factor = 1;
    for (const auto& unit : UNITS) {
        const size_t length = std::strlen(unit.suffix);
        if (number.size() > length && number.compare(number.size() - length, length, unit.suffix) == 0) {
            factor = unit.factor;
            number.resize(number.size() - length);
            break;
        }
    }
    // A decimal number only: strtod would also read "0x1b" (hexadecimal) or "inf".
    if (number.find_first_not_of("0123456789.e+-") != std::string::npos) return false;
    double value;
    if (!parse_number(number, value) || !(value > 0) || value * factor >= 18446744073709551615.0) return false;
    bytes = uint64_t(value * factor);
    return bytes > 0;
}

} // namespace dbrg::cli
