// libFuzzer harness: the pbrt scene reader, from memory. Files it names (Include, plymesh, imagemap)
// are looked up in a folder that does not exist. Bad input must end in a scene (with warnings) or an
// InputError, never a crash, a hang or a sanitizer report.
#include <cstddef>
#include <cstdint>
#include <string>

#include "core/error.h"
#include "io/pbrt_parser.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    try {
        wideray::parsePbrt(std::string(reinterpret_cast<const char*>(data), size), "/nonexistent/fuzz.pbrt");
    } catch (const wideray::InputError&) {
    }
    return 0;
}
