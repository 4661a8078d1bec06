// Pi: the one definition of the constant for the library and its tools.
#pragma once

namespace dbrg {

constexpr double PI = 3.14159265358979323846;

} // namespace dbrg
