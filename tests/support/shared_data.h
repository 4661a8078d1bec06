// Where the reference meshes are: ../shared/data as the build saw it, or DBRG_DATA_DIR at run time.
#pragma once

#include <cstdlib>
#include <string>

namespace dbrg::test {

// Empty when neither is known (a user's clone has no data folder): the tests that need it then skip.
inline std::string shared_data_dir() {
    if (const char* dir = std::getenv("DBRG_DATA_DIR")) return dir;
#ifdef DBRG_SHARED_DATA_DIR
    return DBRG_SHARED_DATA_DIR;
#else
    return "";
#endif
}

} // namespace dbrg::test
