// libFuzzer harness: the glTF 2.0 loader from memory, JSON (.gltf) or binary (.glb, the data starting
// with the magic "glTF"). External buffers and images are looked up in a folder that does not exist.
// Bad input must end in an InputError, never a crash, a hang or a sanitizer report.
#include <cstddef>
#include <cstdint>
#include <string>

#include "core/error.h"
#include "io/mesh_io.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    try {
        wideray::parseGltf(std::string(reinterpret_cast<const char*>(data), size), "/nonexistent/fuzz.gltf");
    } catch (const wideray::InputError&) {
    }
    return 0;
}
