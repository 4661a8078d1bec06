// Where the reference meshes are: ../shared/data as the build saw it, or DBRG_DATA_DIR at run time.
// The test cases that read them belong to the doctest suite SHARED_DATA_SUITE, which tests/meson.build runs
// as a test of its own: without the folder it shows as skipped, not as passed.
#pragma once

#include <doctest/doctest.h>

#include <cstdlib>
#include <filesystem>
#include <string>

namespace dbrg::test {

constexpr const char* SHARED_DATA_SUITE = "shared_data";

// Empty when neither is known.
inline std::string shared_data_dir() {
    if (const char* dir = std::getenv("DBRG_DATA_DIR")) return dir;
#ifdef DBRG_SHARED_DATA_DIR
    return DBRG_SHARED_DATA_DIR;
#else
    return "";
#endif
}

// Notes that the running test case skipped for want of the shared data (test_main.cpp exits with meson's
// skip code when every case that ran did).
void skip_for_missing_data();

// The shared data folder; or, when it is missing (a user's clone has none), "" after noting the skip with
// a message naming where it looked: the test case then returns.
inline std::string shared_data_dir_or_skip() {
    const std::string dir = shared_data_dir();
    std::error_code error;
    if (!dir.empty() && std::filesystem::is_directory(dir, error)) return dir;
    MESSAGE("skipped: no shared data folder at '" << dir << "' (set DBRG_DATA_DIR to point at one)");
    skip_for_missing_data();
    return "";
}

} // namespace dbrg::test
