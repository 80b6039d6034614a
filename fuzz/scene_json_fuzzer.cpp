// libFuzzer harness: the scene reader on arbitrary text. Bad input must end in an InputError (a
// message naming the key or line), never a crash, a hang or a sanitizer report. Mesh files the
// text names are looked up next to a scene path that does not exist, so they fail cleanly too.
#include <cstddef>
#include <cstdint>
#include <string>

#include "core/error.h"
#include "io/scene_parser.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    try {
        wideray::parseScene(std::string(reinterpret_cast<const char*>(data), size), "/nonexistent/fuzz.json");
    } catch (const wideray::InputError&) {
    }
    return 0;
}
