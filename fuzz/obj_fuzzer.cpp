// libFuzzer harness: the OBJ loader with an MTL file, from memory. The input is the OBJ text, then
// after the first NUL byte the text of the MTL file that every mtllib reads. Bad input must end in an
// InputError, never a crash, a hang or a sanitizer report.
#include <cstddef>
#include <cstdint>
#include <string>

#include "core/error.h"
#include "io/mesh_io.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string input(reinterpret_cast<const char*>(data), size);
    const size_t split = input.find('\0');
    try {
        wideray::parseObj(input.substr(0, split), split == std::string::npos ? "" : input.substr(split + 1),
                          "/nonexistent/fuzz.obj");
    } catch (const wideray::InputError&) {
    }
    return 0;
}
