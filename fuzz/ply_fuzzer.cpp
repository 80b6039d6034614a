// libFuzzer harness: the PLY loader (ascii, binary little- and big-endian) from memory. Bad input must
// end in an InputError, never a crash, a hang or an allocation beyond what the input holds.
#include <cstddef>
#include <cstdint>
#include <string>

#include "core/error.h"
#include "io/mesh_io.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    try {
        wideray::parsePly(std::string(reinterpret_cast<const char*>(data), size), "/nonexistent/fuzz.ply");
    } catch (const wideray::InputError&) {
    }
    return 0;
}
