#pragma once
// A file's extension in lower case (".ply"), by which the readers and writers choose a format.
#include <cctype>
#include <filesystem>
#include <string>

namespace wideray {

inline std::string lowercaseExtension(const std::filesystem::path& path) {
    std::string ext = path.extension().string();
    for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
    return ext;
}

} // namespace wideray
