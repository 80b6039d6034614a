#pragma once
/// The one exception the library throws: bad arguments (a mesh index out of range, an unknown kernel
/// name, an unreadable scene file), with a message that says what is wrong and where.
#include <stdexcept>

#include "wideray/export.h"

namespace wideray {

class WIDERAY_API Error : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

} // namespace wideray
