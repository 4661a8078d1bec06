// The dbrg program's option values: sizes with their units, counts and numbers.
#include <doctest/doctest.h>

#include <cstdint>
#include <string>

#include "cli/cli_args.h"

using dbrg::cli::parse_count;
using dbrg::cli::parse_size;

namespace {

uint64_t size_of(const std::string& text) {
    uint64_t bytes = 0;
    REQUIRE_MESSAGE(parse_size(text, bytes), text);
    return bytes;
}

bool refused(const std::string& text) {
    uint64_t bytes = 0;
    return !parse_size(text, bytes);
}

} // namespace

TEST_CASE("sizes: single letters and KiB..TiB are powers of 1024, KB..TB powers of 1000, in any case") {
    CHECK(size_of("1500000000") == 1500000000u);
    CHECK(size_of("1K") == 1024u);
    CHECK(size_of("1k") == 1024u);
    CHECK(size_of("1KiB") == 1024u);
    CHECK(size_of("1kib") == 1024u);
    CHECK(size_of("1KB") == 1000u);
    CHECK(size_of("20M") == size_of("20MiB"));
    CHECK(size_of("20MiB") == 20971520u);
    CHECK(size_of("20MB") == 20000000u);
    CHECK(size_of("1.5G") == 1610612736u);
    CHECK(size_of("2GiB") == (uint64_t(1) << 31));
    CHECK(size_of("2GB") == 2000000000u);
    CHECK(size_of("1T") == (uint64_t(1) << 40));
    CHECK(size_of("3TB") == 3000000000000u);
    CHECK(size_of("20971520B") == 20971520u);
    CHECK(size_of("1b") == 1u);
    CHECK(size_of("1.5b") == 1u);  // rounded down
    CHECK(size_of("1e3K") == 1024000u);
}

TEST_CASE("sizes: no number, no positive whole byte, another unit or notation, or 2^64 and more are refused") {
    for (const char* text : {"", "B", "GiB", "kib", "0.5B", "0", "-1G", "3Q", "1 G", " 1G", "1G ", "1GiBs", "1iB",
                             "0x1b", "0x10", "inf", "nan", "18446744073709551616", "16777216T"}) {
        CAPTURE(text);
        CHECK(refused(text));
    }
}

TEST_CASE("counts are whole numbers below 2^32") {
    uint32_t value = 0;
    CHECK((parse_count("4294967295", value) && value == 4294967295u));
    CHECK_FALSE(parse_count("4294967296", value));
    CHECK_FALSE(parse_count("1.5", value));
    CHECK_FALSE(parse_count("-1", value));
}
