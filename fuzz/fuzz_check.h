// Always-on checks for the fuzz harnesses: a failed check prints what failed and aborts, which libFuzzer
// reports as a crash with the input saved. Unlike assert, it stays on in release builds (the regression
// replays under `meson test` run in them).
#pragma once

#include <stdio.h>
#include <stdlib.h>

namespace dbrg::fuzz {

[[noreturn]] inline void check_failed(const char* condition, const char* detail, const char* file, int line) {
    fprintf(stderr, "%s:%d: check failed: %s%s%s\n", file, line, condition, detail[0] ? " -- " : "", detail);
    abort();
}

} // namespace dbrg::fuzz

#define FUZZ_CHECK(condition) FUZZ_CHECK_WHY(condition, "")

// As FUZZ_CHECK, with a string (evaluated only on failure) that says more.
#define FUZZ_CHECK_WHY(condition, detail)                                                   \
    do {                                                                                    \
        if (!(condition)) ::dbrg::fuzz::check_failed(#condition, (detail), __FILE__, __LINE__); \
    } while (0)
