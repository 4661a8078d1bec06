// Enum fields and arguments from C callers: C lets any int sit in an enum object, but loading a value
// outside the enumerators' range as the C++ enum type is undefined behaviour, so checks read the int.
#pragma once

#include <string.h>

namespace dbrg {

template <class Enum>
int c_enum_value(const Enum& value) {
    static_assert(sizeof(Enum) == sizeof(int), "C enums are int-sized");
    int bits;
    memcpy(&bits, &value, sizeof bits);
    return bits;
}

} // namespace dbrg
