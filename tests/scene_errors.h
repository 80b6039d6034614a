#pragma once
// The message a scene of one object (and a light) is rejected with, for the tests of object keys.
#include <string>

#include "core/error.h"
#include "io/scene_parser.h"

namespace wideray::testing {

/// The InputError's message for a scene whose only object is `object` (JSON); "no error" if it parses.
inline std::string objectError(const std::string& object) {
    try {
        parseScene(R"({"lights": [{"type": "point", "position": [0, 5, 0]}], "objects": [)" + object + "]}", "bad.json");
    } catch (const InputError& e) {
        return e.what();
    }
    return "no error";
}

} // namespace wideray::testing
